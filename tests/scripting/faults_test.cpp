// Faults that used to crash the Lua layer (issue 24), each reproduced first:
// corrupted bytecode through require, dofile and load segfaulted inside
// liblua; getmetatable(m).__gc(m) deleted a model that handles still used.
#include <gtest/gtest.h>

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
