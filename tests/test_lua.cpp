// The command line and the Lua binding: errors as one line "FILE:LINE: message" with exit
// code 1, -v variables, callbacks, computes read from Lua, runs that continue.
#include <gtest/gtest.h>

#include "test_util.hpp"

using pbf::test::run_engine;
using pbf::test::scenario;

namespace {

struct Script {
  pbf::test::TempDir dir{"lua"};
  std::filesystem::path path;
  explicit Script(const std::string& body, const std::string& name = "script.lua") {
    path = dir / name;
    pbf::test::write_file(path, body);
  }
};

// A small scene most scripts start from (lines 1-5).
const std::string kScene =
    "pbf.domain{lo = {0, 0, 0}, hi = {0.2, 0.2, 0.2}}\n"
    "pbf.kernel_radius(0.02)\n"
    "pbf.timestep(0.002)\n"
    "pbf.lattice{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}, spacing = 0.01}\n"
    "pbf.fix('pbf', 'pbf', {})\n";

}  // namespace

TEST(Lua, SyntaxErrorNamesFileAndLine) {
  Script s("local x = 1\npbf.fix('a', 'gravity'\n");
  auto r = run_engine("run " + s.path.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find(s.path.string() + ":3:"), std::string::npos) << r.output;
}

TEST(Lua, RuntimeErrorNamesFileAndLine) {
  Script s("local x = 1\n\nerror('boom')\n");
  auto r = run_engine("run " + s.path.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find(s.path.string() + ":3: boom"), std::string::npos) << r.output;
}

TEST(Lua, LongPathsAreNotShortened) {
  Script s("\nerror('boom')\n", std::string(80, 'x') + ".lua");
  auto r = run_engine("run " + s.path.string());
  EXPECT_NE(r.output.find(s.path.string() + ":2: boom"), std::string::npos) << r.output;
}

TEST(Lua, EngineErrorsCarryTheScriptLine) {
  Script s(kScene + "pbf.fix('g', 'gravity', {accel = {0, 0, -1}})\n");
  auto r = run_engine("run " + s.path.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find(s.path.string() + ":6: fix 'g' (gravity): unknown parameter 'accel'; valid parameters: "
                                            "acceleration"),
            std::string::npos)
      << r.output;
  Script u(kScene + "\npbf.compute('x', 'no_such', {})\n");
  r = run_engine("run " + u.path.string());
  EXPECT_NE(r.output.find(u.path.string() + ":7: unknown compute style 'no_such'; valid compute styles: density"),
            std::string::npos)
      << r.output;
}

TEST(Lua, ErrorIsOneLineOnStderr) {
  Script s("error('boom')\n");
  auto r = run_engine("run " + s.path.string() + " --log-level warn", "2>/dev/null");
  EXPECT_EQ(r.output, "");  // nothing on stdout (the info lines, the first of which names the version, are off)
  r = run_engine("run " + s.path.string(), "2>&1 1>/dev/null");
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

TEST(Lua, VariablesConvertAsLuaNumerals) {
  Script s("print(math.type(var.i), math.type(var.f), math.type(var.e), type(var.s), var.s)\n");
  auto r = run_engine("run " + s.path.string() + " -v i=3 -v f=2.5 -v e=1e3 -v s=abc");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("integer\tfloat\tfloat\tstring\tabc"), std::string::npos) << r.output;
}

TEST(Lua, UnreadVariablesGetAWarning) {
  Script s("local x = var.used\n");
  auto r = run_engine("run " + s.path.string() + " -v used=1 -v typo=2");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.output.find("warning: variable 'typo' given with -v was never read"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("'used'"), std::string::npos) << r.output;
}

TEST(Lua, BadCommandLinesExitWithTwo) {
  EXPECT_EQ(run_engine("run").code, 2);
  EXPECT_EQ(run_engine("frobnicate").code, 2);
  EXPECT_EQ(run_engine("run x.lua --threads 0").code, 2);
  EXPECT_EQ(run_engine("run x.lua -v novalue").code, 2);
  EXPECT_EQ(run_engine("help").code, 0);
  EXPECT_NE(run_engine("help no_such_style").code, 0);
  EXPECT_EQ(run_engine("--version").code, 0);
}

TEST(Lua, MissingScriptIsAnError) {
  auto r = run_engine("run /nonexistent/x.lua");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("/nonexistent/x.lua: cannot open"), std::string::npos);
}

TEST(Lua, ComputesAreReadableAndCallbacksRun) {
  Script s(kScene +
           "pbf.compute('n', 'count')\n"
           "pbf.compute('box', 'extent')\n"
           "pbf.compute('rho', 'density')\n"
           "assert(pbf.value('n') == 1000 and pbf.count() == 1000)\n"
           "assert(math.abs(pbf.value('box').xmax - 0.095) < 1e-6)\n"
           "assert(#pbf.value('rho') == 1000)\n"
           "local calls = 0\n"
           "pbf.every('count', 5, function(step, time) calls = calls + 1; assert(step % 5 == 0) end)\n"
           "pbf.run(20)\n"
           "assert(calls == 4, calls)\n"
           "assert(pbf.step() == 20 and math.abs(pbf.time() - 0.04) < 1e-15)\n"
           "print('done')\n");
  auto r = run_engine("run " + s.path.string());
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("done"), std::string::npos);
}

TEST(Lua, ALatticesVelocityMayBeAFunctionOfPosition) {
  // v = (x, 2y, -z) on the 2 x 2 x 2 sites at 0.005 and 0.015 m: the fastest, at (0.015,
  // 0.015, 0.015), moves at 0.015 sqrt(6) m/s, and the kinetic energy is m/2 times the sum of
  // |v|^2 over the sites, with m the lattice's mass.
  Script s(
      "pbf.domain{lo = {0, 0, 0}, hi = {0.2, 0.2, 0.2}}\npbf.kernel_radius(0.02)\npbf.timestep(0.002)\n"
      "local t = {lo = {0, 0, 0}, hi = {0.02, 0.02, 0.02}, spacing = 0.01,\n"
      "           velocity = function(x, y, z) return {x, 2 * y, -z} end}\n"
      "assert(pbf.lattice(t) == 8 and type(t.velocity) == 'function')\n"
      "pbf.compute('v', 'speed')\npbf.compute('ke', 'kinetic_energy')\npbf.run(0)\n"
      "local sum = 0\n"
      "for _, x in ipairs{0.005, 0.015} do for _, y in ipairs{0.005, 0.015} do for _, z in ipairs{0.005, 0.015} do\n"
      "  sum = sum + x * x + 4 * y * y + z * z end end end\n"
      "local m = pbf.value('ke') / (0.5 * sum)\n"
      "assert(math.abs(pbf.value('v').max / (0.015 * math.sqrt(6)) - 1) < 1e-6, pbf.value('v').max)\n"
      "assert(m > 0.9e-3 and m < 1.1e-3, m)  -- the lattice's mass, about rho0 s^3\n"
      "print('done')\n");
  auto r = run_engine("run " + s.path.string());
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("done"), std::string::npos) << r.output;
  // What the function gives must be a finite vector, and its errors name it and the site.
  const std::pair<std::string, std::string> bad[] = {
      {"return nil", "at (0.005, 0.005, 0.005): its result must be a vector {x, y, z}"},
      {"return {0/0, 0, 0}", "at (0.005, 0.005, 0.005) returned a velocity that is not finite"},
      {"error('nope')", "at (0.005, 0.005, 0.005) failed: "}};
  for (const auto& [body, message] : bad) {
    Script b("pbf.domain{lo = {0, 0, 0}, hi = {0.2, 0.2, 0.2}}\npbf.kernel_radius(0.02)\n"
             "pbf.lattice{lo = {0, 0, 0}, hi = {0.02, 0.02, 0.02}, spacing = 0.01,\n"
             "            velocity = function(x, y, z) " + body + " end}\n");
    auto rb = run_engine("run " + b.path.string());
    EXPECT_EQ(rb.code, 1) << body;
    EXPECT_NE(rb.output.find(b.path.string() + ":3: pbf.lattice: the velocity function " + message), std::string::npos)
        << rb.output;
  }
}

TEST(Lua, ErrorInACallbackNamesTheCallbackLine) {
  Script s(kScene + "pbf.every('cb', 2, function(step)\n  if step == 4 then error('stop here') end\nend)\npbf.run(10)\n");
  auto r = run_engine("run " + s.path.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find(s.path.string() + ":7: stop here"), std::string::npos) << r.output;
}

TEST(Lua, RunsContinueAcrossCallsWithoutRepeatingFrames) {
  Script s(kScene + "pbf.fix('walls', 'box', {})\npbf.fix('d', 'dump/text', {path = var.out .. '/frame_*.txt', every = 5})\n"
                    "pbf.run(5)\npbf.run(5)\npbf.unfix('walls')\npbf.fix('walls', 'box', {friction = 1})\npbf.run(5)\n");
  const auto out = s.dir / "frames";
  auto r = run_engine("run " + s.path.string() + " -v out=" + out.string());
  EXPECT_EQ(r.code, 0) << r.output;
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(std::filesystem::exists(out / ("frame_0000" + std::to_string(k) + ".txt")));
  EXPECT_FALSE(std::filesystem::exists(out / "frame_00004.txt"));
}

TEST(Lua, ABlowUpNamesStepParticleAndFix) {
  // g dt = -1e309 overflows to -inf in the first kick.
  Script s(kScene + "pbf.fix('g', 'gravity', {acceleration = {0, 0, -1e4}})\npbf.timestep(1e305)\npbf.run(3)\n");
  // By default the step's one check finds it, and says how to name the fix.
  auto r = run_engine("run " + s.path.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find(s.path.string() + ":8: step 1: the simulation blew up: particle 0 has a non-finite"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("at the end of the step (run it again with --check-every-hook to name the fix"),
            std::string::npos)
      << r.output;
  // Checked after every hook, it names the fix and the stage.
  r = run_engine("run --check-every-hook " + s.path.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find(s.path.string() + ":8: step 1: the simulation blew up: particle 0 has a non-finite"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("after fix 'g' (gravity) in stage external_forces"), std::string::npos) << r.output;
}

TEST(Lua, LeavingTheDomainIsAnError) {
  Script s("pbf.domain{lo = {0, 0, 0}, hi = {0.2, 0.2, 0.2}}\npbf.kernel_radius(0.02)\npbf.timestep(0.01)\n"
           "pbf.lattice{lo = {0.1, 0.1, 0.1}, hi = {0.12, 0.12, 0.12}, spacing = 0.01, velocity = {1, 0, 0}}\n"
           "pbf.fix('pbf', 'pbf', {})\npbf.run(20)\n");
  auto r = run_engine("run " + s.path.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find(":6: step 9: particle 1 at"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("is outside the domain"), std::string::npos) << r.output;
}

TEST(InitFile, SceneErrorsNameTheSceneFileNotTheScript) {
  const auto dir = pbf::test::temp_dir("init");
  pbf::test::write_file(dir / "bad.txt", "2\n0.002\n0.04\n0.4\n0.01\n0.03\n0.1 0.1 0.1 0 0 0\n0.1 0.1 x 0 0 0\n");
  auto r = run_engine("run " + scenario("init_file.lua") + " -v init=" + (dir / "bad.txt").string() + " -v out=" +
                      (dir / "o").string());
  EXPECT_EQ(r.code, 1);
  const std::string expected = (dir / "bad.txt").string() + ":8: z: 'x' is not a number";
  EXPECT_EQ(r.output.substr(r.output.find(expected) == std::string::npos ? 0 : r.output.find(expected)),
            expected + "\n")
      << r.output;
}

TEST(InitFile, MissingInitVariableIsNamed) {
  auto r = run_engine("run " + scenario("init_file.lua"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("init_file.lua:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("missing variable 'init'"), std::string::npos) << r.output;
}

TEST(Lua, NonStringErrorsNameTheirLine) {
  const std::pair<std::string, std::string> cases[] = {
      {"local x = 1\n\nerror({})\n", ":3: (error object is a table value)"},
      {"error(nil)\n", ":1: (error object is a nil value)"},
      {"\nerror(42)\n", ":2: 42"},
      {"local e = setmetatable({}, {__tostring = function() return 'custom' end})\nerror(e)\n", ":2: custom"},
      // A __tostring that fails leaves the type, not "error in error handling".
      {"error(setmetatable({}, {__tostring = function() error('no') end}))\n", ":1: (error object is a table value)"},
      {"error('no position', 0)\n", ":1: no position"},
  };
  for (const auto& [body, expected] : cases) {
    Script s(body);
    auto r = run_engine("run " + s.path.string());
    EXPECT_EQ(r.code, 1) << body;
    EXPECT_NE(r.output.find(s.path.string() + expected + "\n"), std::string::npos) << body << r.output;
  }
}

TEST(Lua, NonStringErrorInACallbackNamesTheCallbackLine) {
  Script s(kScene + "pbf.every('cb', 2, function(step)\n  if step == 4 then error({}) end\nend)\npbf.run(10)\n");
  auto r = run_engine("run " + s.path.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find(s.path.string() + ":7: (error object is a table value)\n"), std::string::npos) << r.output;
}

TEST(Lua, NestingTooDeepNamesFileAndLine) {
  const std::string deep = std::string(300, '(') + "1" + std::string(300, ')');
  const std::pair<std::string, std::string> cases[] = {
      // The parser's limit: expressions, tables and calls nested in the source.
      {"local x = " + deep + "\n", ":1: C stack overflow (nested too deeply)"},
      {"local a = 1\nlocal t = " + std::string(300, '{') + std::string(300, '}') + "\n", ":2: C stack overflow"},
      {"local function f(x) return x end\n\nlocal y = " + [] {
         std::string s;
         for (int k = 0; k < 300; ++k) s += "f(";
         return s + "1" + std::string(300, ')');
       }() + "\n",
       ":3: C stack overflow (nested too deeply)"},
      // At run time: recursion through C functions (tostring, gsub) and through Lua.
      {"local t\nt = setmetatable({}, {__tostring = function() return tostring(t) end})\nprint(t)\n", ":2: C stack overflow"},
      {"local function f(s) return (string.gsub(s, '.', f)) end\n\nf('ab')\n", ":1: C stack overflow"},
      {"local function f(n) return f(n + 1) + 1 end\nf(1)\n", ":1: stack overflow"},
  };
  for (const auto& [body, expected] : cases) {
    Script s(body);
    auto r = run_engine("run " + s.path.string());
    EXPECT_EQ(r.code, 1) << body.substr(0, 60);
    EXPECT_NE(r.output.find(s.path.string() + expected), std::string::npos) << body.substr(0, 60) << r.output;
  }
}

TEST(Lua, NumbersThatAreNotIntegersAreRefusedBeforeConversion) {
  const std::pair<std::string, std::string> cases[] = {
      {"pbf.run(0/0)", "pbf.run: the number of steps must be an integer, got nan"},
      {"pbf.run(1/0)", "pbf.run: the number of steps must be an integer, got inf"},
      {"pbf.run(-1/0)", "pbf.run: the number of steps must be an integer, got -inf"},
      {"pbf.run(1e300)", "pbf.run: the number of steps must be an integer, got 1e+300"},
      {"pbf.run(2^63)", "pbf.run: the number of steps must be an integer, got 9.223372036854776e+18"},
      {"pbf.run(2.5)", "pbf.run: the number of steps must be an integer, got 2.5"},
      {"pbf.thermo{every = 1/0}", "pbf.thermo: 'every' must be an integer, got inf"},
      {"pbf.thermo{every = -5e18}", "thermo: 'every' must be >= 0, got -5000000000000000000"},
      {"pbf.thermo{every = 5e18}", "pbf.thermo: 'every' is too large"},
      {"pbf.thermo{[1] = 5}", "pbf.thermo: every key must be a name (every, columns or csv), got a number"},
      {"pbf.every('e', 0/0, print)", "pbf.every: the interval in steps must be an integer, got nan"},
  };
  for (const auto& [line, message] : cases) {
    Script s(kScene + line + "\n");
    auto r = run_engine("run " + s.path.string());
    EXPECT_EQ(r.code, 1) << line;
    EXPECT_NE(r.output.find(s.path.string() + ":6: " + message + "\n"), std::string::npos) << line << "\n" << r.output;
  }
  Script s(kScene + "pbf.run(-0.0)\nprint(pbf.step())\n");  // an integral float is an integer
  auto r = run_engine("run " + s.path.string());
  EXPECT_EQ(r.code, 0) << r.output;
}

TEST(Lua, UnknownNamesSuggestTheNearest) {
  const std::pair<std::string, std::string> cases[] = {
      {"pbf.fix('p2', 'pbf', {iteratons = 3})",
       "fix 'p2' (pbf): unknown parameter 'iteratons' (did you mean 'iterations'?); valid parameters: iterations, "},
      {"pbf.fix('g', 'gravty', {})", "unknown fix style 'gravty' (did you mean 'gravity'?); valid fix styles: gravity, "},
      {"pbf.fix('d', 'dump/txt', {})", "unknown fix style 'dump/txt' (did you mean 'dump/text'?); valid fix styles: "},
      {"pbf.compute('k', 'kinetic_enrgy')", "unknown compute style 'kinetic_enrgy' (did you mean 'kinetic_energy'?)"},
      {"pbf.lattice{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}, spacing = 0.01, velocty = {1, 0, 0}}",
       "pbf.lattice: unknown parameter 'velocty' (did you mean 'velocity'?); valid parameters: lo, hi, spacing, velocity"},
      {"pbf.thermo{evry = 5}", "pbf.thermo: unknown key 'evry' (did you mean 'every'?); valid keys: every, columns, csv"},
      {"pbf.compute('err', 'density_error')\npbf.thermo{columns = {'step', 'err.mx'}}",
       "thermo: unknown column 'err.mx' (did you mean 'err.max'?); valid columns now: step, time, dt, particles, "
       "err.avg, err.max, err.compression"},
      {"pbf.thermo{columns = {'ke'}}", "thermo: unknown column 'ke'; valid columns now: step, time, dt, particles"},
  };
  for (const auto& [lines, message] : cases) {
    Script s(kScene + lines + "\n");
    auto r = run_engine("run " + s.path.string());
    EXPECT_EQ(r.code, 1) << lines;
    EXPECT_NE(r.output.find(s.path.string() + ":" + (lines.find('\n') == std::string::npos ? "6" : "7") + ": " + message),
              std::string::npos)
        << lines << "\n" << r.output;
  }
  Script s(kScene + "pbf.fix('d', 'dump/text', {path = var.out .. '/f_*.txt', every = 1, fields = {'velocty'}})\n"
                    "pbf.run(1)\n");
  auto r = run_engine("run " + s.path.string() + " -v out=" + (s.dir / "o").string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find(s.path.string() + ":7: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("unknown field 'velocty' (did you mean 'velocity'?); valid fields: position, velocity"),
            std::string::npos)
      << r.output;
}

TEST(Lua, PrintKeepsLuasFormat) {
  Script s("print(1, 'two', nil, true, 2.5, setmetatable({}, {__tostring = function() return 'obj' end}))\nprint()\n");
  auto r = run_engine("run " + s.path.string() + " --log-level warn");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output, "1\ttwo\tnil\ttrue\t2.5\tobj\n\n");
}

TEST(Lua, StringsWithZeroBytesAreRefused) {
  Script s(kScene + "pbf.fix('d', 'dump/text', {path = 'o/f_*.txt\\0x', every = 1})\n");
  auto r = run_engine("run " + s.path.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find(s.path.string() + ":6: fix 'd' (dump/text): parameter 'path' must not contain a zero byte"),
            std::string::npos)
      << r.output;
  Script t("pbf.read_scene('s.txt\\0.lua')\n");
  r = run_engine("run " + t.path.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find(t.path.string() + ":1: pbf.read_scene: the path must not contain a zero byte"),
            std::string::npos)
      << r.output;
}

TEST(Lua, EmptyPathsAreRefused) {
  for (const std::string function : {"read_scene", "read_particles", "read_restart", "write_restart"}) {
    Script s("\npbf." + function + "('')\n");
    auto r = run_engine("run " + s.path.string());
    EXPECT_EQ(r.code, 1) << function;
    EXPECT_NE(r.output.find(s.path.string() + ":2: pbf." + function + ": the path must not be empty\n"),
              std::string::npos)
        << r.output;
  }
}
