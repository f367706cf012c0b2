// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// A GoogleTest fixture around one in-process Lua state with the dda module:
// a test's SetUp makes the Session and calls start(); run() and error_of()
// execute Lua code as a script would.
#include <gtest/gtest.h>

#include <string>

#include "run_control.hpp"
#include "scripting.hpp"

namespace dda::test {

class LuaStateTest : public ::testing::Test {
 protected:
  void start(script::Session s) {
    L = script::new_state(std::move(s));
    ASSERT_NE(L, nullptr);
  }
  void TearDown() override {
    script::stop_background_runs();  // before the models close (run_control.hpp)
    if (L) lua_close(L);
  }

  // Runs code; fails the test with the message on error.
  void run(const std::string& code) {
    std::string error;
    ASSERT_TRUE(script::run_string(L, code, "test", error)) << error;
  }
  // A global's value (0 / "(nil)" when it is not a number / string).
  double number(const char* global) {
    lua_getglobal(L, global);
    const double v = lua_tonumber(L, -1);
    lua_pop(L, 1);
    return v;
  }
  std::string string(const char* global) {
    lua_getglobal(L, global);
    const std::string v = lua_tostring(L, -1) ? lua_tostring(L, -1) : "(nil)";
    lua_pop(L, 1);
    return v;
  }
  // Runs code expecting an error; returns the message.
  std::string error_of(const std::string& code) {
    std::string error;
    EXPECT_FALSE(script::run_string(L, code, "test", error)) << "no error from:\n" << code;
    return error;
  }

  lua_State* L = nullptr;
};

}  // namespace dda::test
