// pbfengine: the command line.
//   pbfengine run FILE.lua [-v NAME=VALUE]... [--threads N] [--log-level LEVEL]
//   pbfengine help [STYLE] [--markdown]
//   pbfengine --version
// Exit codes: 0 success; 1 an error in the script, a scene file, a parameter or the run
// (one line on stderr, "FILE:LINE: message"); 2 a bad command line; 130 a run stopped by
// Ctrl-C after writing a restart (named on stderr).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <omp.h>
#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include "engine/error.hpp"
#include "engine/interrupt.hpp"
#include "engine/simulation.hpp"
#include "engine/style_registry.hpp"
#include "scripting/script.hpp"

namespace {

// "%*" in the log pattern: "warning: " before warnings and errors, nothing before info,
// so thermo lines stay clean columns.
class LevelPrefix : public spdlog::custom_flag_formatter {
 public:
  void format(const spdlog::details::log_msg& msg, const std::tm&, spdlog::memory_buf_t& dest) override {
    static const std::string warning = "warning: ", error = "error: ", debug = "debug: ";
    const std::string* prefix = nullptr;
    if (msg.level == spdlog::level::warn) prefix = &warning;
    else if (msg.level >= spdlog::level::err) prefix = &error;
    else if (msg.level <= spdlog::level::debug) prefix = &debug;
    if (prefix) dest.append(prefix->data(), prefix->data() + prefix->size());
  }
  std::unique_ptr<custom_flag_formatter> clone() const override { return std::make_unique<LevelPrefix>(); }
};

void setup_logging(const std::string& level) {
  auto logger = spdlog::stdout_logger_mt("pbfengine");
  auto formatter = std::make_unique<spdlog::pattern_formatter>();
  formatter->add_flag<LevelPrefix>('*').set_pattern("%*%v");
  logger->set_formatter(std::move(formatter));
  logger->set_level(spdlog::level::from_str(level));
  logger->flush_on(spdlog::level::info);
  spdlog::set_default_logger(logger);
}

int run_script(const std::string& file, const std::vector<std::string>& assignments) {
  std::vector<std::pair<std::string, std::string>> variables;
  for (const auto& a : assignments) {
    const auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0) {
      std::fprintf(stderr, "pbfengine: -v expects NAME=VALUE, got '%s'\n", a.c_str());
      return 2;
    }
    variables.emplace_back(a.substr(0, eq), a.substr(eq + 1));
  }
  try {
    pbf::Simulation sim;
    pbf::Script script(sim);
    script.set_variables(variables);
    script.run_file(file);
    for (const auto& name : script.unread_variables())
      spdlog::warn("variable '{}' given with -v was never read by {}", name, file);
  } catch (const pbf::Interrupted& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "%s\n", e.what());
    return 130;  // the shell's code for a process ended by SIGINT
  } catch (const std::exception& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"pbfengine: a scriptable Position Based Fluids engine"};
  app.set_version_flag("--version", std::string("pbfengine ") + PBF_VERSION);
  app.require_subcommand(1);

  auto* run = app.add_subcommand("run", "run a Lua scenario script");
  std::string file, level = "info";
  std::vector<std::string> assignments;
  int threads = 0;
  run->add_option("FILE", file, "the scenario script (.lua)")->required();
  run->add_option("-v,--var", assignments, "set var.NAME in the script (repeatable)")->allow_extra_args(false);
  run->add_option("--threads", threads, "OpenMP threads (default: all cores)")->check(CLI::PositiveNumber);
  run->add_option("--log-level", level, "trace, debug, info, warn, error or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));

  auto* help = app.add_subcommand("help", "list styles, or one style's parameters");
  std::string style;
  bool markdown = false;
  help->add_option("STYLE", style, "a fix or compute style");
  help->add_flag("--markdown", markdown, "the scripting reference of every style, as Markdown");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
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

  setup_logging(level);
  if (threads > 0) omp_set_num_threads(threads);
  return run_script(file, assignments);
}
