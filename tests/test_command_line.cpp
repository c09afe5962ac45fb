// The command line: "did you mean" suggestions, --threads and unknown commands refused in
// one line with exit code 2, the version and thread count printed, and the log file (what
// a run prints, with a header; --log FILE, --log none; one warning when it cannot be opened).
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <omp.h>
#include <unistd.h>

#include "engine/core/threads.hpp"
#include "engine/core/vectors.hpp"
#include "engine/core/names.hpp"
#include "test_util.hpp"

using pbf::test::read_file;
using pbf::test::run_engine;
using pbf::test::run_in;
using pbf::test::TempDir;
using pbf::test::write_file;

namespace {

// A small scene with thermo every 5 steps (lines 1-7).
const std::string kScene =
    "pbf.domain{lo = {0, 0, 0}, hi = {0.2, 0.2, 0.2}}\n"
    "pbf.kernel_radius(0.02)\n"
    "pbf.timestep(0.002)\n"
    "pbf.lattice{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}, spacing = 0.01}\n"
    "pbf.fix('pbf', 'pbf', {})\n"
    "pbf.compute('ke', 'kinetic_energy')\n"
    "pbf.thermo{every = 5, columns = {'step', 'time', 'ke'}}\n";

std::size_t lines(const std::string& text) { return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')); }

const int kMachine = static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN));
const std::string kRange = fmt::format("from 1 to {} (4 per hardware thread of this machine)", 4 * kMachine);

}  // namespace

TEST(Names, SuggestsTheNearestNameForATypo) {
  using pbf::nearest_name;
  EXPECT_EQ(nearest_name("iteratons", {"iterations", "epsilon", "scorr_k", "scorr_n"}), "iterations");
  EXPECT_EQ(nearest_name("gravty", {"pbf", "gravity", "box"}), "gravity");
  EXPECT_EQ(nearest_name("dump/txt", {"dump/text", "dump/vtk", "dump/image"}), "dump/text");
  EXPECT_EQ(nearest_name("err.mx", {"step", "time", "err.avg", "err.max"}), "err.max");
  EXPECT_EQ(nearest_name("velocty", {"position", "velocity", "mass"}), "velocity");
  EXPECT_EQ(nearest_name("hlep", {"run", "help"}), "help");       // a swap of neighbours is one edit
  EXPECT_EQ(nearest_name("Gravity", {"pbf", "gravity"}), "gravity");  // case ignored
}

TEST(Names, SuggestsNothingForUnrelatedOrShortNames) {
  using pbf::nearest_name;
  EXPECT_EQ(nearest_name("accel", {"acceleration"}), "");
  EXPECT_EQ(nearest_name("frobnicate", {"run", "help"}), "");
  EXPECT_EQ(nearest_name("ke", {"step", "time", "dt", "particles"}), "");
  EXPECT_EQ(nearest_name("xyz", {"box", "pbf", "cfl"}), "");  // two edits from a 3-letter name is too far
  EXPECT_EQ(nearest_name("", {"a", "b"}), "");
  EXPECT_EQ(nearest_name("speed", {}), "");
  EXPECT_EQ(pbf::did_you_mean("evry", {"every", "columns", "csv"}), " (did you mean 'every'?)");
  EXPECT_EQ(pbf::did_you_mean("dir", {"path", "fields", "interval", "every"}), "");
}

TEST(CommandLine, BadThreadCountsAreOneLineNamingTheRange) {
  for (const std::string given : {"0", "abc", "100000", "-3", "2.5", ""}) {
    auto r = run_engine("run x.lua --threads '" + given + "'", "2>&1 >/dev/null");  // stderr alone
    EXPECT_EQ(r.code, 2) << given;
    EXPECT_EQ(r.output, "pbfengine: --threads must be a whole number " + kRange + ", got '" + given + "'\n");
  }
}

TEST(CommandLine, ThreadCountsFromTheEnvironmentThatAreNoCountAreWarnedAndTheDefaultUsed) {
  const TempDir dir("cli-omp");
  write_file(dir / "a.lua", "print('ran')\n");
  for (const std::string given : {"100000", "0", "many"}) {
    auto r = run_in(dir, "run a.lua --log none", "OMP_NUM_THREADS=" + given);
    EXPECT_EQ(r.code, 0) << r.out << r.err;
    EXPECT_NE(r.err.find("warning: OMP_NUM_THREADS='" + given + "' is not a thread count from 1 to " +
                         std::to_string(4 * kMachine) + ": ignored; the run uses "),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("\nran\n"), std::string::npos) << r.out;
  }
}

TEST(CommandLine, TheFirstLineOfARunGivesVersionAndThreads) {
  const TempDir dir("cli-threads");
  write_file(dir / "a.lua", "print('ran')\n");
  auto r = run_engine("run " + (dir / "a.lua").string() + " --threads 1");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output, fmt::format("pbfengine {} on 1 OpenMP thread (as --threads asks)\nran\n", PBF_VERSION));
  // The default: one per core the process may use (here all it has: ctest gives no limits).
  const auto usable = pbf::cores_of_this_process(1).usable();
  r = run_engine("run " + (dir / "a.lua").string());
  EXPECT_EQ(r.output.rfind(fmt::format("pbfengine {} on {} OpenMP thread{} (one per core this process may use: ",
                                       PBF_VERSION, usable, usable == 1 ? "" : "s"),
                           0),
            0u)
      << r.output;
  // More than that runs, with one warning.
  r = run_engine("run " + (dir / "a.lua").string() + " --threads " + std::to_string(4 * kMachine));
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.rfind(fmt::format("pbfengine {} on {} OpenMP threads (as --threads asks)\nwarning: {} threads on "
                                       "the {} core{} this process may use",
                                       PBF_VERSION, 4 * kMachine, 4 * kMachine, usable, usable == 1 ? "" : "s"),
                           0),
            0u)
      << r.output;
}

TEST(CommandLine, AnUnknownCommandSuggestsOneAndListsThem) {
  auto r = run_engine("hlep");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.output,
            "pbfengine: unknown command 'hlep' (did you mean 'help'?); the commands are run, help "
            "(pbfengine --help says more)\n");
  r = run_engine("frobnicate x.lua");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.output, "pbfengine: unknown command 'frobnicate'; the commands are run, help (pbfengine --help says more)\n");
}

TEST(CommandLine, NoCommandPrintsTheUsage) {
  auto r = run_engine("", "2>&1 >/dev/null");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("Usage: pbfengine [OPTIONS] SUBCOMMAND"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("run a Lua scenario script"), std::string::npos) << r.output;
}

TEST(CommandLine, OtherBadCommandLinesAreOneLine) {
  const std::pair<std::string, std::string> cases[] = {
      {"run", "pbfengine: FILE is required (pbfengine run --help lists the options)\n"},
      {"run x.lua --log-level loud",
       "pbfengine: --log-level: loud not in {trace,debug,info,warn,error,off} (pbfengine run --help lists the options)\n"},
      {"run x.lua -v novalue", "pbfengine: -v expects NAME=VALUE, got 'novalue'\n"},
      {"run x.lua --log ''", "pbfengine: --log needs a file name, or 'none' for no log\n"},
  };
  for (const auto& [args, message] : cases) {
    auto r = run_engine(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(r.output, message) << args;
  }
  auto r = run_engine("help gravty");
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.output, "pbfengine: unknown style 'gravty' (did you mean 'gravity'?); 'pbfengine help' lists them\n");
}

TEST(LogFile, HoldsAHeaderThenWhatTheRunPrinted) {
  const TempDir dir("log");
  write_file(dir / "a.lua", kScene + "print('from Lua', 42)\npbf.run(10)\n");
  auto r = run_in(dir, "run a.lua -v unused=1 --threads 1");
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  // Warnings go to stderr; 'unused' is no typo of a variable the script read, so it is
  // reported at the end (not at the first run).
  EXPECT_EQ(r.err, "warning: variable 'unused' given with -v was never read by a.lua\n");
  const std::string log = read_file(dir / "log.pbfengine");
  // The header: the command line, the start time, the version, the threads and why, how
  // they wait, and the vectors.
  const std::string command = fmt::format("command: {} run a.lua -v unused=1 --threads 1\nstarted: ", PBF_BINARY);
  ASSERT_EQ(log.rfind(command, 0), 0u) << log;
  const std::string time = log.substr(command.size(), log.find('\n', command.size()) - command.size());
  EXPECT_EQ(time.size(), 25u) << time;  // 2026-11-21T14:05:09+01:00
  EXPECT_EQ(time[10], 'T');
  EXPECT_EQ(time[22], ':');
  const std::string header = command + time + "\nversion: pbfengine " + PBF_VERSION +
                             "\nthreads: 1 (as --threads asks)\nwaiting: " + pbf::waiting_policy(1) +
                             "\nvectors: " + pbf::vectors_in_use() + "\n";
  ASSERT_EQ(log.rfind(header, 0), 0u) << log;
  // Then exactly what the run printed, on both streams in the order printed: Lua's print,
  // thermo, the timing table, the warning, the list of what it wrote.
  const std::string printed = log.substr(header.size());
  const std::size_t warning = printed.find(r.err);
  ASSERT_NE(warning, std::string::npos) << printed;
  EXPECT_EQ(printed.substr(0, warning) + printed.substr(warning + r.err.size()), r.out);
  EXPECT_NE(r.out.find("Wrote:\n  log: log.pbfengine\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("from Lua\t42\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("          step          time            ke\n           [-]           [s]           [J]\n"
                       "             0             0             0\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("\n            10          0.02"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Timing: 10 steps"), std::string::npos) << r.out;

  // Each run overwrites the log.
  write_file(dir / "b.lua", "print('second')\n");
  r = run_in(dir, "run b.lua");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string second = read_file(dir / "log.pbfengine");
  EXPECT_EQ(second.find("a.lua"), std::string::npos) << second;
  EXPECT_NE(second.find("\nsecond\n"), std::string::npos) << second;
}

TEST(LogFile, TheErrorEndsTheLog) {
  const TempDir dir("log-error");
  write_file(dir / "a.lua", "print('before')\n\npbf.fix('p', 'pbf', {iteratons = 3})\n");
  auto r = run_in(dir, "run a.lua --log run.log");
  EXPECT_EQ(r.code, 1);
  const std::string message = "a.lua:3: fix 'p' (pbf): unknown parameter 'iteratons' (did you mean 'iterations'?); "
                              "valid parameters: ";
  EXPECT_EQ(r.err.rfind(message, 0), 0u) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  const std::string log = read_file(dir / "run.log");
  EXPECT_FALSE(std::filesystem::exists(dir / "log.pbfengine"));
  EXPECT_NE(log.find("\nbefore\n" + r.err), std::string::npos) << log;  // print, then the error, last
  EXPECT_EQ(log.substr(log.size() - r.err.size()), r.err);
}

TEST(LogFile, NoneWritesNoLog) {
  const TempDir dir("log-none");
  write_file(dir / "a.lua", "print('ran')\n");
  auto r = run_in(dir, "run a.lua --log none");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("ran\n"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir / "log.pbfengine"));
  EXPECT_FALSE(std::filesystem::exists(dir / "none"));
}

TEST(LogFile, ALogThatCannotBeOpenedIsOneWarning) {
  const TempDir dir("log-missing");
  write_file(dir / "a.lua", "print('ran')\n");
  auto r = run_in(dir, "run a.lua --log no/such/dir/x.log");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "warning: cannot open the log file 'no/such/dir/x.log' (No such file or directory); "
                   "the run goes on without a log\n");
  EXPECT_NE(r.out.find("ran\n"), std::string::npos);
  std::filesystem::create_directory(dir / "d");
  r = run_in(dir, "run a.lua --log d");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "warning: cannot open the log file 'd' (Is a directory); the run goes on without a log\n");
}

TEST(LogFile, TheScriptIsNeverOverwritten) {
  const TempDir dir("log-script");
  write_file(dir / "a.lua", "print('ran')\n");
  auto r = run_in(dir, "run a.lua --log ./a.lua");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "pbfengine: the log file './a.lua' is the script itself; choose another with --log\n");
  EXPECT_EQ(read_file(dir / "a.lua"), "print('ran')\n");
  r = run_in(dir, "run b.lua --log " + (dir / "b.lua").string());  // a script not there yet
  EXPECT_EQ(r.code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "b.lua"));
}

TEST(LogFile, CtrlCEndsTheLog) {
  const TempDir dir("log-sigint");
  write_file(dir / "a.lua", kScene + "pbf.every('mark', 1, function(step)\n"
                                     "  if step == 5 then io.open('running', 'w'):close() end end)\n"
                                     "pbf.run(100000000)\n");
  const std::string command = fmt::format(
      "cd '{}' && ( {} run a.lua --threads 1 > stdout 2> stderr & pid=$!; "
      "for i in $(seq 600); do [ -e running ] && break; sleep 0.05; done; kill -INT $pid; wait $pid; echo $? > code )",
      dir.string(), PBF_BINARY);
  ASSERT_EQ(std::system(command.c_str()), 0);
  EXPECT_EQ(read_file(dir / "code"), "130\n");
  // stderr: the warning that the run will take long, then the message, which ends the log.
  const std::string stderr_text = read_file(dir / "stderr"), log = read_file(dir / "log.pbfengine");
  ASSERT_EQ(stderr_text.rfind("warning: run(100000000): ", 0), 0u) << stderr_text;
  const std::string err = stderr_text.substr(stderr_text.find('\n') + 1);
  EXPECT_EQ(err.rfind("interrupted (Ctrl-C) after step ", 0), 0u) << err;
  EXPECT_EQ(log.substr(log.size() - std::min(log.size(), err.size())), err) << log;
}

TEST(CommandLine, AFileSizeLimitIsAnErrorNotASignal) {
  // ulimit -f: a write past the limit raises SIGXFSZ, which would kill the run unreported.
  const TempDir dir("cli-fsize");
  write_file(dir / "a.lua", kScene + "pbf.fix('d', 'dump/text', {path = 'o/f_*.txt', every = 1})\npbf.run(2)\n");
  auto r = run_in(dir, "run a.lua --log run.log", "ulimit -f 8 &&");  // 8 KiB; a frame is about 60
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(r.err.rfind("a.lua:9: fix 'd' (dump/text): ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  const std::string log = read_file(dir / "run.log");
  EXPECT_EQ(log.substr(log.size() - std::min(log.size(), r.err.size())), r.err) << log;
}
