// pbfengine: the command line.
//   pbfengine run FILE.lua [-v NAME=VALUE]... [--threads N] [--log FILE|none] [--log-level LEVEL]
//                 [--vectors NAME] [--check-every-hook]
//   pbfengine help [STYLE] [--markdown]
//   pbfengine --version
// Exit codes: 0 success; 1 an error in the script, a scene file, a parameter or the run
// (one line on stderr, "FILE:LINE: message"); 2 a bad command line (one line on stderr,
// or the usage when no command is given); 130 a run stopped by Ctrl-C after writing a
// restart (named on stderr).
// What a run prints also goes to a log file (log.pbfengine unless --log says otherwise).
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <chrono>
#include <filesystem>
#include <thread>
#include <omp.h>
#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/core/vectors.hpp"
#include "engine/core/interrupt.hpp"
#include "engine/core/names.hpp"
#include "engine/core/simulation.hpp"
#include "engine/core/threads.hpp"
#include "engine/registry/style_registry.hpp"
#include "scripting/log_file.hpp"
#include "scripting/script.hpp"

namespace {

// A bad command line: one line on stderr, exit code 2.
int command_line_error(const std::string& message) {
  std::fprintf(stderr, "pbfengine: %s\n", message.c_str());
  return 2;
}

// The end of a failed run (an error, Ctrl-C): one line on stderr, and in the log.
void report(const std::string& message) {
  std::fflush(stdout);  // what the run printed comes first
  std::fprintf(stderr, "%s\n", message.c_str());
  pbf::log_file::write(message + "\n");
}

std::string thread_range() {
  return fmt::format("from 1 to {} (4 per hardware thread of this machine)", pbf::thread_limit());
}

// --threads N: a whole number in 1 .. thread_limit(); nothing when the text is not one.
std::optional<int> parse_threads(const std::string& text) {
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos) return {};
  const int n = std::stoi(text);  // at most 9 digits: fits an int
  if (n < 1 || n > pbf::thread_limit()) return {};
  return n;
}

// --view PORT: a whole number 0 .. 65535; nothing when the text is not one.
std::optional<int> parse_port(const std::string& text) {
  if (text.empty() || text.size() > 5 || text.find_first_not_of("0123456789") != std::string::npos) return {};
  const int n = std::stoi(text);
  if (n > 65535) return {};
  return n;
}

// --view: the `view` fix the command line adds before the script runs.
struct ViewOptions {
  int port;
  std::string address;
  bool allow_remote;
};

// Now, local time, in ISO 8601: 2026-11-21T14:05:09+01:00.
std::string iso8601_now() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char text[64];
  std::string s(text, std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S%z", &local));
  if (s.size() > 5) s.insert(s.size() - 2, ":");  // strftime's +0100 is ISO 8601's +01:00
  return s;
}

// The command line as a shell would take it back: words with other than plain characters
// in single quotes.
std::string command_line(const std::vector<std::string>& words) {
  std::string line;
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::string& word = words[i];
    const bool plain = !word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                               "0123456789_-+=/.,:@%") == std::string::npos;
    std::string quoted = "'";
    for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += (i ? " " : "") + (plain ? word : quoted + "'");
  }
  return line;
}

// A distributed run that failed on some rank: one message, then every rank stops (none waits
// for a partner that is gone). An error every rank meets (a script's) is rank 0's to tell;
// the others wait a moment first, so that rank 0 tells it and ends them all. One that only
// another rank meets (a particle of its own that blew up) that rank tells, naming itself.
int fail(const std::string& message, int code) {
  if (!pbf::comm::distributed()) {
    report(message);
    return code;
  }
  if (pbf::comm::root()) {
    report(message);
  } else {
    std::this_thread::sleep_for(std::chrono::seconds(2));
    std::fflush(stdout);
    std::fprintf(stderr, "rank %d: %s\n", pbf::comm::rank(), message.c_str());
  }
  std::fflush(stderr);
  pbf::log_file::close();
  pbf::comm::abort(code);
}

// How to continue from RESTART, appended to the message of a run that stopped or failed: the
// same command line with -v restart=PATH when the script reads var.restart (pbf.scene does),
// else the function that reads it.
std::string continuation(const std::string& restart, const pbf::Script& script, std::vector<std::string> words) {
  if (!script.reads_variable("restart"))
    return fmt::format("; continue from it with pbf.read_restart('{}') in place of the scene, or pbf.scene "
                       "(docs/user-guide.md#continuing-a-run-exactly)",
                       restart);
  // The command line without its own -v restart (-v restart=P, -vrestart=P, --var restart=P, --var=restart=P).
  std::vector<std::string> kept;
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::string& w = words[i];
    const bool option = w == "-v" || w == "--var";
    if (option && i + 1 < words.size() && words[i + 1].rfind("restart=", 0) == 0) {
      ++i;
      continue;
    }
    if (w.rfind("-vrestart=", 0) == 0 || w.rfind("--var=restart=", 0) == 0) continue;
    kept.push_back(w);
  }
  kept.push_back("-v");
  kept.push_back("restart=" + restart);
  // The ranks of a distributed run see their own command line, not the launcher's.
  const std::string launcher = pbf::comm::distributed() ? fmt::format("mpirun -np {} ", pbf::comm::ranks()) : "";
  return fmt::format("; continue with: {}{} (docs/user-guide.md#continuing-a-run-exactly)", launcher,
                     command_line(kept));
}

// The end of a script that ran (or was stopped): what it wrote, in one list.
void list_outputs(const pbf::Simulation& sim, const std::string& log_path) {
  std::string list = sim.outputs().summary();
  if (log_path != "none") list += fmt::format("  log: {}\n", log_path);
  if (!list.empty()) spdlog::info("Wrote:\n{}", list.substr(0, list.size() - 1));
}

// The debugging aids of `pbfengine run` (Simulation::set_check_every_hook, set_check_ghosts).
struct DebugChecks {
  bool every_hook = false, ghosts = false;
};

int run_script(const std::string& file, const std::vector<std::pair<std::string, std::string>>& variables,
               const DebugChecks& checks, const std::optional<ViewOptions>& view, std::vector<std::string> words,
               const std::string& log_path) {
  std::unique_ptr<pbf::Simulation> sim;
  std::unique_ptr<pbf::Script> script;
  try {
    sim = std::make_unique<pbf::Simulation>();
    sim->set_check_every_hook(checks.every_hook);
    sim->set_check_ghosts(checks.ghosts);
    if (view) {  // served before the script runs: a port in use stops the command at once
      try {
        sim->add_fix(pbf::StyleRegistry::builtin().make_fix(
            "view", "view",
            {{"port", std::int64_t{view->port}},
             {"address", view->address},
             {"allow_remote", view->allow_remote},
             {"title", std::filesystem::path(file).filename().string()}}));
      } catch (const pbf::Error& e) {
        std::string message = e.what();
        const std::string fix = "fix 'view' (view): ";
        if (message.rfind(fix, 0) == 0) message.erase(0, fix.size());
        return fail(fmt::format("--view: {}", message), 1);
      }
      // A continuation serves on the port this run took, where a page left open looks for it.
      const int port = sim->find_fix("view")->run_view()->port();
      for (std::size_t i = 0; i < words.size(); ++i) {
        if (words[i] == "--view" && i + 1 < words.size()) words[i + 1] = std::to_string(port);
        if (words[i].rfind("--view=", 0) == 0) words[i] = fmt::format("--view={}", port);
      }
    }
    script = std::make_unique<pbf::Script>(*sim);
    script->set_variables(variables);
    script->run_file(file);
    for (const auto& warning : script->unread_variable_warnings()) spdlog::warn("{}", warning);
    list_outputs(*sim, log_path);
  } catch (const pbf::Interrupted& e) {
    // Every rank of a distributed run stops after the same step (they agree on the signal),
    // so they end together, as one process would: no abort.
    list_outputs(*sim, log_path);
    if (pbf::comm::root()) report(e.what() + continuation(e.restart(), *script, words));
    return 130;  // the shell's code for SIGINT
  } catch (const std::exception& e) {
    // A failed step names the newest restart, which is whole.
    const std::string restart = sim ? sim->last_restart().path : "";
    const bool names_it = script && !restart.empty() && std::string(e.what()).find("'" + restart + "'") != std::string::npos;
    return fail(e.what() + (names_it ? continuation(restart, *script, words) : ""), 1);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"pbfengine: a scriptable Position Based Fluids engine", "pbfengine"};
  app.set_version_flag("--version", std::string("pbfengine ") + PBF_VERSION);
  app.require_subcommand(1);

  auto* run = app.add_subcommand("run", "run a Lua scenario script");
  std::string file, level = "info", threads_text, log_path = "log.pbfengine";
  std::vector<std::string> assignments;
  run->add_option("FILE", file, "the scenario script (.lua)")->required();
  run->add_option("-v,--var", assignments, "set var.NAME in the script (repeatable)")->allow_extra_args(false);
  run->add_option("--threads", threads_text,
                  "OpenMP threads, 1 to 4 x the hardware threads (default: one per core this process may use)")
      ->type_name("N");
  run->add_option("--log", log_path, "copy what the run prints into this file, or 'none' (default: log.pbfengine)")
      ->type_name("FILE");
  run->add_option("--log-level", level, "trace, debug, info, warn, error or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));
  DebugChecks checks;
  run->add_flag("--check-every-hook", checks.every_hook,
                "check for non-finite positions and velocities after every fix, naming the one that produced "
                "them (a debugging aid; by default once a step)");
  run->add_flag("--check-ghosts", checks.ghosts,
                "in one process, read every neighbour through a ghost copy and fill scratch arrays with NaN "
                "before each fix, so a fix that misses a ghost refresh (what MPI runs need) changes the result "
                "or stops the run (a debugging aid for writing fixes)");
  std::string view_port_text, view_address = "127.0.0.1";
  bool view_allow_remote = false;
  run->add_option("--view", view_port_text,
                  "watch the run live in a web browser: serve it on this port of 127.0.0.1 (0: a free one; the "
                  "address to open is printed; docs/view.md)")
      ->type_name("PORT");
  run->add_option("--view-address", view_address,
                  "serve the view on this address (only with --view-allow-remote unless it is the loopback)")
      ->type_name("ADDRESS");
  run->add_flag("--view-allow-remote", view_allow_remote,
                "allow --view-address to be an address other machines reach (anyone with the token can stop the run)");
  std::string vectors = "auto";
  run->add_option("--vectors", vectors,
                  "widest vector instructions of the pair loops: auto (the widest this machine has), avx512, avx2, "
                  "sse4 or none; every choice gives the same bits")
      ->type_name("NAME");

  auto* help = app.add_subcommand("help", "list styles, or one style's parameters");
  std::string style;
  bool markdown = false;
  help->add_option("STYLE", style, "a fix or compute style");
  help->add_flag("--markdown", markdown, "the scripting reference of every style, as Markdown");

  // Before CLI11, which answers both of these with "A subcommand is required".
  if (argc < 2) {
    std::fputs(app.help().c_str(), stderr);
    return 2;
  }
  std::vector<std::string> commands;
  for (const auto* sub : app.get_subcommands([](CLI::App*) { return true; })) commands.push_back(sub->get_name());
  if (argv[1][0] != '-' && std::find(commands.begin(), commands.end(), argv[1]) == commands.end())
    return command_line_error(fmt::format("unknown command '{}'{}; the commands are {} (pbfengine --help says more)",
                                          argv[1], pbf::did_you_mean(argv[1], commands), fmt::join(commands, ", ")));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    const std::string command = *run ? "pbfengine run" : *help ? "pbfengine help" : "pbfengine";
    return command_line_error(fmt::format("{} ({} --help lists the options)", e.what(), command));
  }

  if (*help) {
    const auto& registry = pbf::StyleRegistry::builtin();
    if (markdown) {
      std::fputs(registry.markdown_reference().c_str(), stdout);
      return 0;
    }
    if (style.empty()) {
      std::fputs(registry.help().c_str(), stdout);
      std::fputs("Scripted callbacks: pbf.every(id, N, function(step, time) ... end); see docs/scripting.md\n", stdout);
      return 0;
    }
    try {
      std::fputs(registry.help(style).c_str(), stdout);
      return 0;
    } catch (const pbf::Error& e) {
      std::fprintf(stderr, "pbfengine: %s\n", e.what());
      return 1;
    }
  }

  // The whole command line is checked before anything runs or the log is opened.
  std::vector<std::pair<std::string, std::string>> variables;
  for (const auto& a : assignments) {
    const auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0) return command_line_error(fmt::format("-v expects NAME=VALUE, got '{}'", a));
    variables.emplace_back(a.substr(0, eq), a.substr(eq + 1));
  }
  std::optional<int> requested_threads;
  if (run->count("--threads")) {
    requested_threads = parse_threads(threads_text);
    if (!requested_threads)
      return command_line_error(
          fmt::format("--threads must be a whole number {}, got '{}'", thread_range(), threads_text));
  }
  if (log_path.empty()) return command_line_error("--log needs a file name, or 'none' for no log");
  std::optional<ViewOptions> view;
  if (run->count("--view")) {
    const std::optional<int> port = parse_port(view_port_text);
    if (!port)
      return command_line_error(
          fmt::format("--view must be a port number from 0 to 65535 (0: a free one), got '{}'", view_port_text));
    view = ViewOptions{*port, view_address, view_allow_remote};
  } else if (run->count("--view-address") || view_allow_remote) {
    return command_line_error("--view-address and --view-allow-remote go with --view PORT");
  }
  try {
    pbf::limit_vectors(vectors);
  } catch (const pbf::Error& e) {
    return command_line_error(fmt::format("--vectors: {}", e.what()));
  }
  // Opening the log truncates it: never the script (compared as absolute paths with links
  // resolved, as either may not exist yet).
  const auto resolved = [](const std::string& path) {
    std::error_code ec;
    return std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
  };
  if (log_path != "none" && resolved(log_path) == resolved(file))
    return command_line_error(fmt::format("the log file '{}' is the script itself; choose another with --log", log_path));

  // Threads that wait without taking the cores they share: set before the OpenMP runtime
  // loads, by starting again (engine/core/threads.hpp); before MPI starts and the log opens.
  // A run of one thread never waits for another: it needs no restart (the ranks of an MPI
  // run learn their share of the node only once MPI has started).
  if (pbf::comm::launched_by_mpi() ||
      pbf::choose_threads(pbf::cores_of_this_process(1), requested_threads, std::getenv("OMP_NUM_THREADS")).threads > 1)
    pbf::restart_with_polite_waiting(argv);
  // Under an MPI launcher: the ranks of a distributed run. Rank 0 alone prints and keeps the log.
  pbf::comm::start(argc, argv);
  const pbf::ThreadChoice threads = pbf::choose_threads(pbf::cores_of_this_process(pbf::comm::ranks_on_node()),
                                                        requested_threads, std::getenv("OMP_NUM_THREADS"));
  if (!pbf::comm::root()) {
    level = "off";
    log_path = "none";
  }
  // A write past the file-size limit (ulimit -f, a full quota) would kill the process with
  // SIGXFSZ; ignored, the write fails (EFBIG) and the engine reports it, naming the file.
  std::signal(SIGXFSZ, SIG_IGN);
  pbf::log_file::setup_logging(level);
  if (log_path != "none") {
    const std::string why = pbf::log_file::open(log_path);
    if (!why.empty())
      std::fprintf(stderr, "warning: cannot open the log file '%s' (%s); the run goes on without a log\n",
                   log_path.c_str(), why.c_str());
    else
      pbf::log_file::write(fmt::format(
          "command: {}\nstarted: {}\nversion: pbfengine {}\nthreads: {} ({})\nwaiting: {}\nvectors: {}\n",
          command_line(std::vector<std::string>(argv, argv + argc)), iso8601_now(), PBF_VERSION, threads.threads, threads.why,
          pbf::waiting_policy(threads.threads),
          pbf::vectors_in_use()));
  }
  omp_set_num_threads(threads.threads);
  const char* s = threads.threads == 1 ? "" : "s";
  if (pbf::comm::distributed())
    spdlog::info("pbfengine {} on {} MPI ranks of {} OpenMP thread{} each ({})", PBF_VERSION, pbf::comm::ranks(),
                 threads.threads, s, threads.why);
  else
    spdlog::info("pbfengine {} on {} OpenMP thread{} ({})", PBF_VERSION, threads.threads, s, threads.why);
  for (const std::string& warning : threads.warnings) spdlog::warn("{}", warning);
  const int code = run_script(file, variables, checks, view, std::vector<std::string>(argv, argv + argc),
                              log_path);
  pbf::comm::stop();
  if (!pbf::log_file::close())
    std::fprintf(stderr, "warning: writing the log file '%s' failed; it is incomplete\n", log_path.c_str());
  return code;
}
