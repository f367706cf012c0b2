// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Faults that used to crash the Lua layer, each reproduced first:
// corrupted bytecode through require, dofile and load segfaulted inside
// liblua; getmetatable(m).__gc(m) deleted a model that handles still used.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "lua_state_test.hpp"
#include "script_helpers.hpp"
#include "scripting.hpp"

using namespace dda::script;

namespace {

class Faults : public dda::test::LuaStateTest {
 protected:
  void SetUp() override {
    dir_ = std::make_unique<dda::test::TempDir>(::testing::UnitTest::GetInstance()->current_test_info()->name());
    Session s;
    s.out_dir = dir_->path / "out";
    start(std::move(s));
    // Modules are looked up in the temporary folder; `dir` names it.
    run("package.path = '" + (dir_->path / "?.lua").string() + "'\ndir = '" + dir_->path.string() + "/'");
  }
  // A function's bytecode with one byte of its instructions overwritten (a
  // flipped disk block): liblua 5.4 loads it and segfaults running it.
  void write_corrupted_bytecode(const std::string& name) {
    run("local code = string.dump(function(a) local t = {} for i = 1, a do t[i] = i * i end return t end)\n"
        "local bad = code:sub(1, 46) .. '\\255' .. code:sub(48)\n"
        "local f = assert(io.open(dir .. '" +
        name +
        "', 'wb'))\n"
        "f:write(bad) f:close()\n"
        "corrupted = bad");
  }
  std::unique_ptr<dda::test::TempDir> dir_;
};

TEST_F(Faults, CorruptedBytecodeModuleIsRefusedByRequire) {
  write_corrupted_bytecode("badmod.lua");
  const std::string e = error_of("require 'badmod'");
  EXPECT_NE(e.find("error loading module 'badmod'"), std::string::npos) << e;
  EXPECT_NE(e.find("binary chunk"), std::string::npos) << e;
  EXPECT_NE(e.find("test:1:"), std::string::npos) << e;
}

TEST_F(Faults, CorruptedBytecodeIsRefusedByDofileLoadfileAndLoad) {
  write_corrupted_bytecode("bad.luac");
  std::string e = error_of("dofile(dir .. 'bad.luac')");
  EXPECT_NE(e.find("test:1: dofile:"), std::string::npos) << e;
  EXPECT_NE(e.find("binary chunk"), std::string::npos) << e;
  e = error_of("\nlocal f, why = loadfile(dir .. 'bad.luac')\nassert(f, why)");
  EXPECT_NE(e.find("binary chunk"), std::string::npos) << e;
  e = error_of("\n\nload(corrupted, 'x', 'b')");
  EXPECT_NE(e.find("test:3: load: binary chunks (precompiled bytecode) are refused"), std::string::npos) << e;
  e = error_of("local f, why = load(corrupted)\nassert(f, why)(3)");
  EXPECT_NE(e.find("attempt to load a binary chunk"), std::string::npos) << e;
  e = error_of("loadfile(dir .. 'bad.luac', 'b')");
  EXPECT_NE(e.find("loadfile: binary chunks"), std::string::npos) << e;
  // Source text still loads every way.
  run("assert(load('return 1 + 1', 'x', 't')() == 2)\nassert(load('return 3')() == 3)");
  dda::test::write_file(dir_->path / "good.lua", "return {value = 7}");
  run("assert(require('good').value == 7)\nassert(dofile(dir .. 'good.lua').value == 7)");
}

TEST_F(Faults, MissingDofileTargetNamesTheLine) {
  const std::string e = error_of("\ndofile(dir .. 'missing.lua')");
  EXPECT_NE(e.find("test:2: dofile: cannot open"), std::string::npos) << e;
}

TEST_F(Faults, ModelMetatableIsProtected) {
  run("m = dda.model{}\n"
      "m:rock{ density = 2000, E = 1e9, nu = 0.25 }\n"
      "mt = getmetatable(m)");
  // The metatable is not reachable, so its __gc cannot be called by hand.
  const std::string e = error_of("getmetatable(m).__gc(m)");
  EXPECT_NE(e.find("attempt to call a nil value"), std::string::npos) << e;
  // The model is still whole: it takes a second material and reports itself.
  run("assert(mt == 'dda.Model')\n"
      "assert(m:rock{ density = 2500, E = 2e9, nu = 0.2 })\n"
      "assert(tostring(m):find('dda.Model %(0 blocks'))");
}

}  // namespace

namespace {

// Two blocks on the ground, for the tests below.
const char* kTwoBlocks =
    "m = dda.model{ gravity = {0, -9.81}, g1 = 1e-4 }\n"
    "local rock = m:rock{ density = 2000, E = 1e9, nu = 0.25 }\n"
    "m:domain{ box = {0, 0, 2, 1}, rock = rock }\n"
    "m:joint_set{ dip = 90, spacing = 1 }\n"
    "m:generate()\n";

class ScriptFaults : public Faults {};

TEST_F(ScriptFaults, ClosingTheModelInsideALoadFunctionIsRefused) {
  // The functions run when the load is given (and before each step): m:close()
  // there freed the World under the call (SIGSEGV, a member call on null).
  const char* cases[] = {
      "m:edges{ on_segment = {0, 0, 0, 1} }:pressure(function(t) m:close() return 0 end)",
      "m:point_load{ at = {0.5, 0.5}, force = function(t) m:close() return 1, 0 end }",
      "m:target{ at = {0.5, 0.5}, direction = {1, 0}, displacement = function(t) m:close() return 0 end }",
      "m:run{ steps = 2, callback = function(mm) "
      "  m:point_load{ at = {1.5, 0.5}, force = function(t) m:close() return 1, 0 end } end }",
  };
  for (const char* c : cases) {
    run(kTwoBlocks);
    const std::string e = error_of(c);
    EXPECT_NE(e.find("m:close: the model cannot be changed or stepped from inside a load history function"),
              std::string::npos)
        << c << "\n"
        << e;
    run("m:step() m:close()");  // the model is still whole
  }
}

TEST_F(ScriptFaults, ThreadsAreBounded) {
  // 1e7 segfaulted inside TBB; 3e9 wrapped to a negative number in the message.
  std::string e = error_of("dda.model{ threads = 1e7 }");
  EXPECT_NE(e.find("option 'threads' must be zero (every core) or 1 to 4096, got 10000000"), std::string::npos) << e;
  e = error_of("dda.model{ threads = 3e9 }");
  EXPECT_NE(e.find("got 3000000000"), std::string::npos) << e;
  e = error_of("m = dda.model{}\nm:controls{ open_close_limit = 3e9 }");
  EXPECT_NE(e.find("option 'open_close_limit' must be at most 2147483647, got 3000000000"), std::string::npos) << e;
  run("m = dda.model{ threads = 4096 }\nassert(m:controls().threads == 4096)");
}

TEST_F(ScriptFaults, FramesEveryZeroIsRefused) {
  run(kTwoBlocks);
  const std::string e = error_of("m:frames{ every = 0 }");
  EXPECT_NE(e.find("m:frames: option 'every' must be a whole number of steps >= 1, got 0"), std::string::npos) << e;
}

TEST_F(ScriptFaults, ATruncatedAccelerogramIsRefused) {
  // 743 of the 1,845 values its header announces: was read as a short record.
  std::ifstream in(std::string(DDA_SOURCE_DIR) + "/data/imperial_valley_1979_el_centro_array7_S50W.dat");
  std::string line, text;
  int values = 0;
  while (std::getline(in, line) && values < 743) {
    if (line.empty() || line[0] != '%') {
      std::istringstream words(line);
      std::string w, kept;
      while (values < 743 && words >> w) kept += " " + w, ++values;
      line = kept;
    }
    text += line + "\n";
  }
  dda::test::write_file(dir_->path / "short.dat", text);
  const std::string e = error_of("\ndda.ground_motion{ file = dir .. 'short.dat' }");
  EXPECT_NE(e.find("test:2: dda.ground_motion: accelerogram '"), std::string::npos) << e;
  EXPECT_NE(e.find("short.dat' is truncated: its header announces 1845 values, it holds 743"), std::string::npos) << e;
}

TEST_F(ScriptFaults, AHoleOfATrillionSegmentsIsRefusedBeforeMakingThem) {
  run("m = dda.model{}\nm:domain{ box = {0, 0, 2, 1}, rock = m:rock{ density = 2000, E = 1e9, nu = 0.25 } }");
  const std::string e = error_of("m:hole{ circle = {1, 0.5, 0.2}, segments = 1e12 }");
  EXPECT_NE(e.find("m:hole: a circle of 1000000000000 segments needs about 1e+06 GB of memory"), std::string::npos)
      << e;
  EXPECT_NE(e.find("give fewer segments (option 'segments', 32 by default)"), std::string::npos) << e;
}

TEST_F(ScriptFaults, MessagesSayNanWithoutASign) {
  // 0/0 is a NaN with its sign bit set: streams printed "-nan".
  const std::string e = error_of("dda.model{ g2 = 0/0 }");
  EXPECT_NE(e.find("got nan"), std::string::npos) << e;
  EXPECT_EQ(e.find("-nan"), std::string::npos) << e;
  EXPECT_EQ(dda::msg(-std::nan("")), "nan");
}

TEST_F(ScriptFaults, ABowTieIsSelfIntersectingNotZeroArea) {
  run("m = dda.model{}\nrock = m:rock{ density = 2000, E = 1e9, nu = 0.25 }");
  const std::string e = error_of("m:add_block{ polygon = {{0, 0}, {1, 1}, {1, 0}, {0, 1}}, rock = rock }");
  EXPECT_NE(e.find("polygon is self-intersecting (edges 1 and 3 cross)"), std::string::npos) << e;
}

}  // namespace
