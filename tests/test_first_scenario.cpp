// A newcomer's first scenario, through the command line as a user runs it: a misspelt -v
// variable reported when the first run starts; -v restart given to a script that cannot
// continue refused there; pbf.scene continuing a run; the command line that Ctrl-C prints
// continuing it exactly; a fresh run over a continued run's restarts said loudly; the list
// of what a run wrote; a step too large for the spacing warned about.
#include <gtest/gtest.h>

#include <algorithm>
#include <fmt/format.h>
#include <regex>

#include "test_util.hpp"

using pbf::test::read_file;
using pbf::test::run_in;
using pbf::test::TempDir;
using pbf::test::write_file;

namespace {

// A column of 2000 particles that builds its scene with pbf.scene, so that -v restart=FILE
// continues it; restarts every 100 steps into out/; 300 steps in all (var.steps).
const std::string kColumn = R"(pbf.scene(function()
  pbf.domain{lo = {0, 0, 0}, hi = {0.2, 0.2, 0.4}}
  pbf.kernel_radius(0.02)
  pbf.timestep(0.002)
  pbf.lattice{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.2}, spacing = 0.01}
end)
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("frames", "dump/text", {path = "out/frame_*.txt", interval = 0.1})
pbf.fix("restarts", "restart", {path = "out/column.*.restart", every = 100})
)";
const std::string kRun = "pbf.run((var.steps or 300) - pbf.step())\n";

std::size_t count(const std::string& text, const std::string& words) {
  std::size_t n = 0;
  for (auto at = text.find(words); at != std::string::npos; at = text.find(words, at + 1)) ++n;
  return n;
}

}  // namespace

// A typo of a variable the script reads is reported at the first run's start, on stderr,
// with the name it was probably meant to be: the log (both streams, in order) has the
// warning before the run's thermo header.
TEST(FirstScenario, AMisspeltVariableIsReportedWhenTheFirstRunStarts) {
  const TempDir dir("first-typo");
  write_file(dir / "a.lua", kColumn + "pbf.compute('ke', 'kinetic_energy')\n"
                                      "pbf.thermo{every = 10, columns = {'step', 'ke'}}\n" + kRun);
  const auto r = run_in(dir, "run a.lua -v stpes=20 --threads 1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "warning: variable 'stpes' given with -v has not been read by a.lua before its first run "
                   "(did you mean 'steps'?)\n");
  const std::string log = read_file(dir / "log.pbfengine");
  EXPECT_LT(log.find("warning: variable 'stpes'"), log.find("          step            ke")) << log;
  EXPECT_EQ(count(log, "warning:"), 1u) << log;  // not again at the end
}

// -v restart to a script that never reads var.restart: refused at the pbf.run line, before
// the run writes over the frames of the run it was meant to continue.
TEST(FirstScenario, ARestartTheScriptCannotContinueIsRefusedBeforeItsRun) {
  const TempDir dir("first-restart-unread");
  const std::string scene = kColumn.substr(kColumn.find("end)\n") + 5);  // the pipeline alone
  write_file(dir / "a.lua", "pbf.domain{lo = {0, 0, 0}, hi = {0.2, 0.2, 0.4}}\npbf.kernel_radius(0.02)\n"
                            "pbf.timestep(0.002)\n"
                            "pbf.lattice{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.2}, spacing = 0.01}\n" +
                                scene + kRun);
  ASSERT_EQ(run_in(dir, "run a.lua -v steps=100").code, 0);
  const std::string frame = read_file(dir / "out/frame_00001.txt");
  const auto r = run_in(dir, "run a.lua -v steps=150 -v restart=out/column.100.restart");
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err.rfind("a.lua:10: -v restart was given, but a.lua has not read var.restart before its first run", 0),
            0u)
      << r.err;
  EXPECT_EQ(read_file(dir / "out/frame_00001.txt"), frame);
}

// Ctrl-C prints the command line that continues, and that command, run as printed, ends
// where the run that was not stopped ends, bit for bit, its thermo CSV included (the rows
// before the restart kept, the rest written again).
TEST(FirstScenario, TheCommandCtrlCPrintsContinuesTheRunExactly) {
  const TempDir dir("first-ctrl-c");
  write_file(dir / "a.lua", kColumn +
                                "pbf.every('ctrl_c', 150, function(step) if step == var.stop then "
                                "io.popen('kill -INT $PPID'):close() end end)\n"
                                "pbf.compute('ke', 'kinetic_energy')\n"
                                "pbf.thermo{every = 20, columns = {'step', 'time', 'ke'}, csv = 'out/thermo.csv'}\n" +
                                kRun + "pbf.write_restart(var.final)\n");
  // Stopped at step 150, as Ctrl-C stops it.
  const auto straight = run_in(dir, "run a.lua -v final=straight.restart --log none -v stop=150 --threads 1");
  ASSERT_EQ(straight.code, 130) << straight.err;
  const std::string message = straight.err.substr(straight.err.rfind("interrupted"));
  const std::regex form(R"(interrupted \(Ctrl-C\) after step 150 \(t = [0-9.]+ s\): wrote restart )"
                        R"('out/column\.150\.restart'; continue with: (.*) \(docs/user-guide\.md#continuing-a-run-exactly\)\n)");
  std::smatch match;
  ASSERT_TRUE(std::regex_match(message, match, form)) << message;
  const std::string command = match[1];
  EXPECT_NE(command.find(" -v restart=out/column.150.restart"), std::string::npos) << command;
  EXPECT_NE(command.find(" -v stop=150 --threads 1 "), std::string::npos) << command;  // the rest kept
  const std::string continue_command = fmt::format("cd '{}' && {} > /dev/null 2>&1", dir.string(), command);
  ASSERT_EQ(std::system(continue_command.c_str()), 0) << command;
  const std::string csv_continued = read_file(dir / "out/thermo.csv");
  // Again from step 200, which the CSV is past: its rows from step 200 on are written again.
  ASSERT_EQ(run_in(dir, "run a.lua -v final=again.restart --log none -v restart=out/column.200.restart").code, 0);
  const std::string csv_again = read_file(dir / "out/thermo.csv");
  // The run that was not stopped: one process to step 300.
  ASSERT_EQ(run_in(dir, "run a.lua -v final=whole.restart --log none").code, 0);
  const std::string whole = read_file(dir / "whole.restart"), continued = read_file(dir / "straight.restart");
  ASSERT_FALSE(whole.empty());
  EXPECT_TRUE(whole == continued);
  const std::string csv_whole = read_file(dir / "out/thermo.csv");
  EXPECT_EQ(std::count(csv_whole.begin(), csv_whole.end(), '\n'), 2 + 16);  // units, names, steps 0, 20, ..., 300
  EXPECT_EQ(csv_continued, csv_whole);
  EXPECT_EQ(csv_again, csv_whole);
}

// A fresh run where the restart fix finds restarts of a later step (a run it was perhaps
// meant to continue) says, once, that it writes over that run's outputs, and how to continue.
TEST(FirstScenario, AFreshRunOverLaterRestartsSaysItWritesOverThem) {
  const TempDir dir("first-over");
  write_file(dir / "a.lua", kColumn + kRun);
  ASSERT_EQ(run_in(dir, "run a.lua").code, 0);
  const auto r = run_in(dir, "run a.lua -v steps=50");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "warning: fix 'restarts' (restart): 'out/column.300.restart' is the restart of a run that reached "
                   "step 300; this run starts at step 0 and writes over that run's outputs (to continue it instead, "
                   "run the script with -v restart=out/column.300.restart and build the scene with pbf.scene)\n");
  // A continued run is no such case.
  const auto continued = run_in(dir, "run a.lua -v steps=400 -v restart=out/column.300.restart");
  EXPECT_EQ(continued.code, 0);
  EXPECT_EQ(continued.err, "");
}

// The run ends with a list of what it wrote, whose counts are the files on disk.
TEST(FirstScenario, TheRunEndsWithAListOfWhatItWrote) {
  const TempDir dir("first-wrote");
  write_file(dir / "a.lua", kColumn + "pbf.compute('ke', 'kinetic_energy')\n"
                                      "pbf.thermo{every = 50, columns = {'step', 'ke'}, csv = 'out/thermo.csv'}\n" +
                                      kRun);
  const auto r = run_in(dir, "run a.lua --log run.log");
  ASSERT_EQ(r.code, 0) << r.err;
  std::size_t frames = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir / "out"))
    frames += entry.path().filename().string().rfind("frame_", 0) == 0;
  EXPECT_EQ(frames, 7u);  // t = 0, 0.1, ..., 0.6 s
  const std::string list = r.out.substr(r.out.find("Wrote:\n"));
  EXPECT_EQ(list, "Wrote:\n"
                  "  frames of fix 'frames' (dump/text): 7 files, out/frame_00000.txt ... out/frame_00006.txt\n"
                  "  thermo CSV: out/thermo.csv\n"
                  "  restarts: 3 files, out/column.100.restart ... out/column.300.restart (1 older removed, 2 kept)\n"
                  "  log: run.log\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "out/column.100.restart"));
  EXPECT_TRUE(std::filesystem::exists(dir / "out/column.200.restart"));
}

// A column at half the usual spacing with a step and iterations that leave it compressed
// well beyond PBF's 1% (the density_error compute measures over 3% for the whole run) is
// warned about once; at a third of that step it stays near 1% and nothing is said.
TEST(FirstScenario, AStepTooLargeForTheSpacingIsWarnedAboutOnce) {
  const TempDir dir("first-dt");
  write_file(dir / "a.lua", R"(
pbf.domain{lo = {0, 0, 0}, hi = {0.4, 0.1, 0.4}}
pbf.kernel_radius(0.01)
pbf.timestep(var.dt)
pbf.lattice{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.2}, spacing = 0.005}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {iterations = 2})
pbf.fix("walls", "box", {})
pbf.compute("err", "density_error")
pbf.run(var.steps)
print("compression", pbf.value("err").compression)
)");
  auto r = run_in(dir, "run a.lua -v dt=0.003 -v steps=70 --log none");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_GT(std::stod(r.out.substr(r.out.find("compression\t") + 12)), 0.03) << r.out;  // the warning's threshold
  EXPECT_EQ(count(r.err, "warning:"), 1u) << r.err;
  EXPECT_NE(r.err.find("warning: fix 'pbf' (pbf): the fluid's mean compression has stayed above 3% for 50 steps"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("the time step 0.003 s is too large for the kernel radius 0.01 m with 2 iterations; about "),
            std::string::npos)
      << r.err;
  // What a fixed count leaves falls with the step (half the step halves it, docs/physics.md
  // "Iterations"): a third of the step leaves about a third, 1.5% is half the warning's 3%.
  r = run_in(dir, "run a.lua -v dt=0.001 -v steps=210 --log none");  // the same 0.21 s
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_LT(std::stod(r.out.substr(r.out.find("compression\t") + 12)), 0.015) << r.out;
  EXPECT_EQ(r.err, "");
}
