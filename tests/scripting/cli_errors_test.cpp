// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// `dda run` on scripts with mistakes: the message names the script, the line,
// the call and the argument; the exit code is non-zero; CSV files written so
// far stay readable. Also --set, Ctrl-C and the command line itself.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "script_helpers.hpp"

using namespace dda::test;

namespace {

const char* kHeader =
    "local m = dda.model{ plane = 'stress', gravity = {0, -9.81}, g1 = 0.01, g2 = 0.5 }\n"  // line 1
    "local rock = m:rock{ density = 2000, E = 5e9, nu = 0.25 }\n";                          // line 2

struct ErrorCase {
  const char* name;
  const char* body;      // script lines after kHeader (line 3 on)
  int line;              // expected line of the error
  const char* expected;  // substring of the message
};

class ScriptErrors : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(ScriptErrors, NameFileLineCallAndArgument) {
  const ErrorCase& c = GetParam();
  TempDir dir(std::string("err-") + c.name);
  write_file(dir / "bad.lua", std::string(kHeader) + c.body);
  const auto r = run_dda("run bad.lua --quiet --out out", dir.path);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const std::string where = "bad.lua:" + std::to_string(c.line) + ":";
  EXPECT_NE(r.err.find(where), std::string::npos) << "expected '" << where << "' in:\n" << r.err;
  EXPECT_NE(r.err.find(c.expected), std::string::npos) << "expected '" << c.expected << "' in:\n" << r.err;
  if (std::string(c.name) != "syntax_error") {  // a chunk that does not compile never ran
    EXPECT_NE(r.err.find("stack traceback"), std::string::npos) << r.err;
  }
}

const ErrorCase kCases[] = {
    {"wrong_type", "local j = m:joint{ friction = 'steep' }\n", 3,
     "m:joint: option 'friction' must be a number, got string"},
    {"unknown_option", "local j = m:joint{ friction = 30, cohesoin = 1e6 }\n", 3,
     "m:joint: unknown option 'cohesoin' (did you mean 'cohesion'?)"},
    {"negative_spacing", "m:domain{ box = {0, 0, 2, 1} }\nm:joint_set{ dip = 0, spacing = -0.2 }\n", 4,
     "m:joint_set: option 'spacing' must be positive, got -0.2"},
    {"unknown_field",
     "m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1} }\nm:monitor{ at = {0.5, 0.5}, fields = {'sxx', 'sigma'} }\n", 4,
     "m:monitor: unknown field 'sigma'"},
    {"missing_option", "m:domain{ box = {0, 0, 2, 1} }\nm:joint_set{ spacing = 0.2 }\n", 4,
     "m:joint_set: option 'dip' is required"},
    {"bad_point", "m:add_block{ {0, 0}, {1, 0}, {1}, {0, 1} }\n", 3,
     "m:add_block: the outline point 3 must be a point {x, y}"},
    {"wrong_self", "m.step(5)\n", 3, "m:step: expected a model as self"},
    {"misspelt_method", "m:stpe(5)\n", 3, "has no method or field 'stpe' (did you mean 'step'?)"},
    {"engine_error", "m:add_block{ {0, 0}, {1, 0}, {0, 1}, {1, 1} }\n", 3, "m:add_block: block 0"},
    {"closed_model", "local b = m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1} }\nm:close()\nprint(b:area())\n", 5,
     "b:area: attempt to use a block of a closed model"},
    {"other_model",
     "local b = m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1} }\nlocal m2 = dda.model{}\nm2:rock{density = 1, E = 1, nu "
     "= 0}\n"
     "m2:edges{ block = b }\n",
     6, "m:edges: option 'block' belongs to another model"},
    {"bad_history",
     "m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1} }\nm:point_load{ at = {0.5, 0.5}, fx = {{0, 1}, {'x', 2}} }\n", 4,
     "m:point_load: option 'fx' entry 2 {t, value} must be a point {x, y} of finite numbers"},
    {"history_returns_nil",
     "m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1} }\n"
     "m:point_load{ at = {0.5, 0.5}, fx = function(t) if t > 0.05 then return nil end return 0 end }\n"
     "m:step(20)\n",
     5, "returned nil at t ="},
    {"runtime_error", "local x = nil\nprint(x.y)\n", 4, "attempt to index a nil value"},
    {"syntax_error", "local x = = 1\n", 3, "unexpected symbol"},
    {"unknown_controls", "m:controls{ g3 = 1 }\n", 3, "m:controls: unknown option 'g3'"},
    {"bad_plane", "local m2 = dda.model{ plane = 'stretch' }\n", 3,
     "dda.model: option 'plane' must be \"stress\" or \"strain\""},
    {"no_block_at_point", "m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1} }\nm:fix(5, 5)\n", 4,
     "m:fix: no block at (5, 5)"},
};

INSTANTIATE_TEST_SUITE_P(Cases, ScriptErrors, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return std::string(info.param.name); });

// An error halfway through a run: the CSV holds the header and one complete
// row per step up to the error, and the message points at the failing line.
TEST(CliErrors, ErrorHalfwayKeepsTheCsvWrittenSoFar) {
  TempDir dir("halfway");
  write_file(dir / "halfway.lua", std::string(kHeader) +
                                      "m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1} }\n"
                                      "m:monitor{ name = 'half', at = {0.5, 0.5}, fields = {'uy', 'vy', 'sxx'} }\n"
                                      "m:run{ steps = 100, callback = function(model)\n"
                                      "  if model:steps() == 50 then error('stopped on purpose') end\n"  // line 6
                                      "end }\n");
  const auto r = run_dda("run halfway.lua --quiet --out out", dir.path);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("halfway.lua:6: stopped on purpose"), std::string::npos) << r.err;
  const Csv csv = read_csv(dir / "out/half.csv");
  EXPECT_TRUE(csv.complete);
  ASSERT_EQ(csv.header, (std::vector<std::string>{"step", "time", "uy", "vy", "sxx"}));
  ASSERT_EQ(csv.rows.size(), 51u);  // steps 0..50
  for (std::size_t i = 0; i < csv.rows.size(); ++i) EXPECT_EQ(csv.rows[i][0], double(i));
}

// An engine error halfway (a step that cannot be taken) is reported the same way.
TEST(CliErrors, EngineErrorHalfwayKeepsTheCsv) {
  TempDir dir("engine_halfway");
  write_file(dir / "diverge.lua", std::string(kHeader) +
                                      "m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1} }\n"
                                      "local mon = m:monitor{ name = 'h', at = {0.5, 0.5}, fields = {'uy'} }\n"
                                      "m:step(10)\n"
                                      "m:controls{ g2 = 1e-12, max_step_cuts = 2 }\n"
                                      "m:step(10)\n");  // line 7
  const auto r = run_dda("run diverge.lua --quiet --out out", dir.path);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("diverge.lua:7: m:step: step 11"), std::string::npos) << r.err;
  const Csv csv = read_csv(dir / "out/h.csv");
  EXPECT_TRUE(csv.complete);
  EXPECT_EQ(csv.rows.size(), 11u);
}

TEST(CliErrors, BytecodeIsRefused) {
  TempDir dir("bytecode");
  write_file(dir / "binary.lua", std::string("\x1bLua\x54\x00 not really bytecode", 25));
  const auto r = run_dda("run binary.lua --quiet", dir.path);
  EXPECT_EQ(r.exit_code, 1);
  // The message names the script (it had no file before).
  EXPECT_NE(r.err.find("binary.lua: binary chunks (precompiled bytecode) are refused"), std::string::npos) << r.err;
}

TEST(CliErrors, MissingScript) {
  TempDir dir("missing");
  const auto r = run_dda("run nowhere.lua --quiet", dir.path);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("cannot open nowhere.lua"), std::string::npos) << r.err;
}

// A command-line error: exit status 2, the cause and one line of usage that
// names the command's --help (not the whole help).
TEST(CliErrors, BadCommandLine) {
  TempDir dir("cli");
  for (const char* args :
       {"run x.lua --bogus", "run x.lua --set novalue", "run x.lua --threads -1", "run x.lua --threads 5000",
        "run x.lua --vtu 99999999999999999999", "run", "frobnicate", "", "console --frames", "sweep x.lua"}) {
    const auto r = run_dda(args, dir.path);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_LE(std::count(r.err.begin(), r.err.end(), '\n'), 2) << args << ":\n" << r.err;
    EXPECT_NE(r.err.find("usage: dda "), std::string::npos) << args << ":\n" << r.err;
  }
  EXPECT_NE(run_dda("run x.lua --frame x", dir.path).err.find("did you mean '--frames'?"), std::string::npos);
  EXPECT_NE(run_dda("run x.lua --bogus", dir.path).err.find("dda run --help"), std::string::npos);
}

// --help on dda and on each command: exit status 0, its usage and options on stdout.
TEST(CliErrors, HelpOnEveryCommand) {
  TempDir dir("help");
  for (const auto& [args, usage] : {std::pair{"--help", "Usage: dda run SCRIPT.lua"},
                                    {"-h", "  or:  dda sweep"},
                                    {"run --help", "Usage: dda run SCRIPT.lua"},
                                    {"run x.lua -h", "Usage: dda run SCRIPT.lua"},
                                    {"console --help", "Usage: dda console"},
                                    {"sweep --help", "dda sweep SCRIPT.lua --grid"}}) {
    const auto r = run_dda(args, dir.path);
    EXPECT_EQ(r.exit_code, 0) << args << ":\n" << r.err;
    EXPECT_NE(r.out.find(usage), std::string::npos) << args << ":\n" << r.out;
    EXPECT_NE(r.out.find("--out"), std::string::npos) << args << ":\n" << r.out;
  }
}

// --set values reach the script through dda.param: numbers when numeric,
// strings otherwise, booleans when the default is one; defaults otherwise;
// a non-number for a numeric default is an error; unread names are warned about.
TEST(CliParams, SetValuesReachTheScript) {
  TempDir dir("params");
  write_file(dir / "params.lua",
             "print('n', dda.param('n', 1), math.type(dda.param('n', 1)))\n"
             "print('x', dda.param('x', 0.5))\n"
             "print('s', dda.param('s', 'default'))\n"
             "print('b', dda.param('b', true))\n"
             "print('d', dda.param('d', 42))\n"
             "print('out', dda.out_dir())\n");
  const auto r = run_dda(
      "run params.lua --quiet --out results --set n=7 --set x=2.5e-3 --set s=hello --set b=false "
      "--set typo=1",
      dir.path);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("n\t7\tinteger"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("x\t0.0025"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("s\thello"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("b\tfalse"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("d\t42"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("out\tresults"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("--set typo=1 was never read"), std::string::npos) << r.err;

  const auto bad = run_dda("run params.lua --quiet --set n=seven", dir.path);
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("params.lua:1: dda.param: --set n=seven is not a number"), std::string::npos) << bad.err;
}

// Ctrl-C during a run: the run stops at a step boundary, the CSV keeps every
// complete row, and dda exits with 130.
TEST(CliInterrupt, SigintStopsAtAStepBoundaryAndKeepsTheCsv) {
  TempDir dir("sigint");
  write_file(dir / "long.lua", std::string(kHeader) +
                                   "m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1} }\n"
                                   "m:monitor{ name = 'long', at = {0.5, 0.5}, fields = {'uy', 'vy'} }\n"
                                   "m:controls{ g1 = 1e-6 }\n"
                                   "m:run{ steps = 100000000 }\n");
  const std::string exe = dda_exe().string();
  const std::string script = (dir / "long.lua").string();
  const std::string out = (dir / "out").string();
  const char* argv[] = {exe.c_str(), "run", script.c_str(), "--quiet", "--out", out.c_str(), nullptr};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  const std::string err_file = (dir / "stderr.txt").string();
  posix_spawn_file_actions_addopen(&actions, 2, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, exe.c_str(), &actions, nullptr, const_cast<char* const*>(argv), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  // Wait until some rows are written.
  const auto csv_path = dir / "out/long.csv";
  for (int i = 0; i < 600; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (read_csv(csv_path).rows.size() >= 20) break;
  }
  kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  const std::string err = read_file(err_file);
  EXPECT_NE(err.find("interrupted"), std::string::npos) << err;
  const Csv csv = read_csv(csv_path);
  EXPECT_TRUE(csv.complete);
  EXPECT_GE(csv.rows.size(), 20u);
  for (std::size_t i = 0; i < csv.rows.size(); ++i) EXPECT_EQ(csv.rows[i][0], double(i));
}

// The console: expressions print, statements run, multi-line input
// continues, errors print a traceback and the console stays up.
TEST(Console, ReadsEvaluatesPrintsAndSurvivesErrors) {
  TempDir dir("console");
  write_file(dir / "setup.lua",
             "m = dda.model{ plane = 'stress', gravity = {0, -9.81}, g1 = 0.01, g2 = 0.5 }\n"  // globals: the
             "rock = m:rock{ density = 2000, E = 5e9, nu = 0.25 }\n"                           // console sees them
             "b = m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1} }\n");
  write_file(dir / "input.txt",
             "m:step(10)\n"
             "1 + 1\n"
             "for i = 1, 2 do\n"
             "  print('line', i)\n"
             "end\n"
             "error('oops')\n"
             "m:stpe(1)\n"
             "x = select(2, b:centroid())\n"
             "x\n");
  const auto r = run_dda("console setup.lua --quiet --out out", dir.path, dir / "input.txt");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("0.1\t10"), std::string::npos) << r.out;  // m:step returns t, steps
  EXPECT_NE(r.out.find("\n2\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("line\t1\nline\t2"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("stdin:1: oops"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("stack traceback"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("did you mean 'step'?"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("0.45095"), std::string::npos) << r.out;  // the block fell 1/2 g t^2 = 0.04905
}

#ifdef DDA_HAVE_RENDER
// dda run --frames N: every model writes a frame every N steps.
TEST(CliFrames, FramesEveryNStepsFromTheCommandLine) {
  TempDir dir("cli_frames");
  const auto r =
      run_dda("run " + quote((source_dir() / "scripts/free_fall.lua").string()) +
                  " --quiet --out out --set t_end=0.2 --frames 10 --frame-field velocity --frame-size 160x120",
              dir.path);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (int i = 0; i <= 2; ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "out/frames/velocity_%05d.png", i);
    EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;
  }
  EXPECT_EQ(run_dda("run x.lua --frames 10 --frame-field sigma_zz", dir.path).exit_code, 2);
  EXPECT_EQ(run_dda("run x.lua --frames 0", dir.path).exit_code, 2);
  EXPECT_EQ(run_dda("run x.lua --frame-size 100", dir.path).exit_code, 2);
  // Values the renderer refuses are the command line's errors, not the
  // script line's that makes the model (was: "x.lua:1: dda.model: frame size ...").
  write_file(dir / "x.lua", "dda.model{}\n");
  for (const char* bad : {"--frame-size 9000x9000", "--frame-range -inf,inf"}) {
    const auto e = run_dda(std::string("run x.lua --frames 10 ") + bad, dir.path);
    EXPECT_EQ(e.exit_code, 2) << bad << "\n" << e.err;
    EXPECT_NE(e.err.find("dda: --frame-size, --frame-range, --frame-view: "), std::string::npos) << e.err;
    EXPECT_EQ(e.err.find("x.lua:"), std::string::npos) << e.err;
  }
}
#endif

// A script that fails in the console is reported and the prompt still starts.
TEST(Console, ScriptErrorLeavesTheConsoleUp) {
  TempDir dir("console_err");
  write_file(dir / "broken.lua", "x = 5\nerror('broken script')\n");
  write_file(dir / "input.txt", "x * 2\n");
  const auto r = run_dda("console broken.lua --quiet", dir.path, dir / "input.txt");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.err.find("broken.lua:2: broken script"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("10"), std::string::npos) << r.out;
}

}  // namespace
