// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Runs in the background (m:start, m:pause, m:resume, m:stop, m:wait,
// m:running): a run paused and resumed at arbitrary steps, with thread counts
// that differ, ends bit for bit where the straight run ends (m:hash(): the
// blocks' vertices, velocities, stresses, the contacts and the time); a
// change made while paused equals the same change made between two stepping
// calls at that step; the model can be read but not changed while it runs;
// the run's error reaches m:wait(); real-time pacing holds a run back.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "lua_state_test.hpp"
#include "run_control.hpp"
#include "script_helpers.hpp"

using namespace dda::script;

namespace {

class BackgroundRun : public dda::test::LuaStateTest {
 protected:
  void SetUp() override {
    out_ = std::make_unique<dda::test::TempDir>(::testing::UnitTest::GetInstance()->current_test_info()->name());
    Session s;
    s.out_dir = out_->path;
    start(std::move(s));
    run(kScene);
  }

  // Blocks of a 2 m x 1 m grid dropped 1 mm onto a fixed base, under
  // gravity, pushed on the left by a pressure: a Lua function of t when
  // `lua_load` (the background run then takes Lua for each step's loads,
  // and steps only while Lua is free: between the script's API calls), else
  // the same as a table; `threads` workers.
  static constexpr const char* kScene =
      "function scene(threads, lua_load)\n"
      "  local m = dda.model{ plane = 'stress', g1 = 1e-3, gravity = {0, -9.81}, threads = threads }\n"
      "  local rock = m:rock{ density = 2000, E = 1e9, nu = 0.25 }\n"
      "  local joint = m:joint{ friction = 30 }\n"
      "  m:add_block{ {-1, -1}, {3, -1}, {3, 0}, {-1, 0}, rock = rock, joint = joint }\n"
      "  m:fix(-0.5, -0.5)\n"
      "  m:fix(2.5, -0.5)\n"
      "  for j = 0, 1 do for i = 0, 3 do\n"
      "    local x, y = 0.5 * i, 0.001 + 0.5 * j\n"
      "    m:add_block{ {x, y}, {x + 0.5, y}, {x + 0.5, y + 0.5}, {x, y + 0.5}, rock = rock, joint = joint }\n"
      "  end end\n"
      "  local left = m:edges{ on_segment = {0, 0, 0, 1.1} }\n"
      "  if lua_load then left:pressure(function(t) return 2e4 * t end)\n"
      "  else left:pressure{ {0, 0}, {1, 2e4} } end\n"
      "  return m\n"
      "end\n"
      "function busy(n) local x = 0 for k = 1, n do x = x + k end return x end\n";

  std::unique_ptr<dda::test::TempDir> out_;
};

}  // namespace

class BackgroundRunLoads : public BackgroundRun, public ::testing::WithParamInterface<bool> {};

TEST_P(BackgroundRunLoads, PausedAndResumedRunIsBitIdenticalToAStraightRun) {
  run(GetParam() ? "lua_load = true" : "lua_load = false");
  run("a = scene(1, lua_load)\n"
      "a:run{ steps = 400 }\n"
      "straight = a:hash()\n"
      "b = scene(2, lua_load)\n"
      "b:start{ steps = 400 }\n"
      "pauses, steps_seen = 0, {}\n"
      "while b:running() do\n"
      "  busy(20000)\n"
      "  local _, s, paused = b:pause()\n"
      "  if paused then\n"
      "    pauses = pauses + 1\n"
      "    steps_seen[#steps_seen + 1] = s\n"
      "    busy(5000)\n"
      "    local _, s2 = b:pause()\n"
      "    assert(s2 == s, 'a step was taken while paused')\n"
      "    assert(b:resume(), 'a paused run did not resume')\n"
      "  end\n"
      "end\n"
      "t, steps = b:wait()\n"
      "resumed = b:hash()\n"
      "distinct = 0\n"
      "for i = 2, #steps_seen do if steps_seen[i] ~= steps_seen[i - 1] then distinct = distinct + 1 end end\n");
  EXPECT_EQ(number("steps"), 400);
  EXPECT_GE(number("pauses"), 3) << "the run should have been paused several times";
  EXPECT_GE(number("distinct"), 2) << "the pauses should fall at different steps";
  EXPECT_EQ(string("resumed"), string("straight"));
}

INSTANTIATE_TEST_SUITE_P(LoadsInLuaOrNot, BackgroundRunLoads, ::testing::Bool());

// `#edges` (a metamethod) lets go of the model it reads when it returns, as
// every API call does: a run started after it steps while the script polls
// (it held the model for good, and the poll below timed out). On a closed
// model it raises a Lua error naming the call (it aborted the program).
TEST_F(BackgroundRun, EdgeSetLengthHoldsItsModelOnlyForTheCall) {
  run("b = scene(2, false)\n"
      "n = #b:edges{}\n"
      "b:start{ steps = 30 }\n"
      "local c0 = os.clock()\n"
      "while b:running() and os.clock() - c0 < 20 do busy(20000) end\n"
      "ran_while_polled = b:running() and 0 or 1\n"
      "b:wait()\n"
      "e = b:edges{}\n"
      "b:close()\n"
      "ok, closed_error = pcall(function() return #e end)\n");
  EXPECT_GT(number("n"), 0);
  EXPECT_EQ(number("ran_while_polled"), 1) << "the run did not step while the script polled m:running()";
  EXPECT_EQ(string("closed_error"),
            "test:10: #edges: attempt to use an edge set of a closed model (m:close() was called)");
}

TEST_F(BackgroundRun, ChangeWhilePausedEqualsTheSameChangeBetweenTwoRuns) {
  run("b = scene(1, false)\n"
      "b:start{ steps = 300 }\n"
      "local c0 = os.clock()\n"
      "repeat busy(10000) until b:steps() >= 20 or os.clock() - c0 > 30\n"
      "_, at = b:pause()\n"
      "b:gravity(0, -3)\n"
      "b:controls{ g1 = 5e-4 }\n"
      "b:resume()\n"
      "b:wait()\n"
      "changed = b:hash()\n"
      "a = scene(1, false)\n"
      "a:run{ steps = at }\n"
      "a:gravity(0, -3)\n"
      "a:controls{ g1 = 5e-4 }\n"
      "a:run{ steps = 300 - at }\n"
      "between = a:hash()\n"
      "same_steps = a:steps() == b:steps()\n");
  EXPECT_GT(number("at"), 0) << "paused before the first step: the test shows nothing";
  EXPECT_LT(number("at"), 300) << "paused after the end: the test shows nothing";
  EXPECT_TRUE(lua_getglobal(L, "same_steps") == LUA_TBOOLEAN && lua_toboolean(L, -1));
  lua_pop(L, 1);
  EXPECT_EQ(string("changed"), string("between"));
}

TEST_F(BackgroundRun, ReadWhileRunningChangeOnlyWhenPaused) {
  run("b = scene(1, false)\n"
      "b:start{ steps = 100000 }\n"
      "running, state = b:running()\n"
      "t0 = b:time()\n"
      "local c0 = os.clock()\n"
      "repeat busy(10000) until b:time() > t0 or os.clock() - c0 > 30\n"
      "t1 = b:time()\n"
      "n_contacts = #b:contacts()\n");
  EXPECT_EQ(string("state"), "running");
  EXPECT_GT(number("t1"), number("t0")) << "the run did not go on while the script ran";
  const std::string e = error_of("b:gravity(0, -1)");
  EXPECT_NE(e.find("m:pause() it first"), std::string::npos) << e;
  EXPECT_NE(error_of("b:step(1)").find("running in the background"), std::string::npos);
  run("b:pause()\n"
      "b:gravity(0, -1)\n"
      "paused_state = select(2, b:running())\n");
  EXPECT_EQ(string("paused_state"), "paused");
  EXPECT_NE(error_of("b:wait()").find("paused"), std::string::npos);
  EXPECT_NE(error_of("b:start{ steps = 1 }").find("in progress"), std::string::npos);
  run("b:resume()\n"
      "t_stop, s_stop = b:stop()\n"
      "stopped = select(2, b:running())\n"
      "b:step(1)\n");
  EXPECT_EQ(string("stopped"), "stopped");
}

TEST_F(BackgroundRun, TheRunsErrorReachesWait) {
  run("b = scene(1, false)\n"
      "b:edges{ on_segment = {3, -1, 3, 0} }:pressure(function(t)\n"
      "  if t > 0.02 then error('boom at ' .. t) end\n"
      "  return 0\n"
      "end)\n"
      "b:start{ time = 1 }\n");
  const std::string e = error_of("b:wait()");
  EXPECT_NE(e.find("background run failed"), std::string::npos) << e;
  EXPECT_NE(e.find("boom at"), std::string::npos) << e;
  run("failed_state = select(2, b:running())\n");
  EXPECT_EQ(string("failed_state"), "failed");
}

// realtime = 1: 0.3 s of simulated time takes at least 0.3 s of wall clock
// (the schedule is kept by waiting; this scene runs far faster unpaced).
TEST_F(BackgroundRun, RealTimePacingHoldsTheRunToTheClock) {
  const auto start = std::chrono::steady_clock::now();
  run("p = dda.model{ g1 = 0.01, gravity = {0, -9.81} }\n"
      "p:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1}, rock = p:rock{ density = 2000, E = 1e9, nu = 0.25 } }\n"
      "p:run{ time = 0.3, realtime = 1 }\n");
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(wall, 0.29);
  ::testing::internal::CaptureStderr();
  run("q = scene(1, false)\n"
      "q:run{ time = 0.05, realtime = 100 }\n");
  const std::string said = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(said.find("could not keep up"), std::string::npos) << said;
}

// The run's end and a pause cannot cross: once a run has no step left a
// pause is refused (it would say "paused" of a run that then ends, and the
// resume would find nothing to resume); a pause that came first holds the
// run at its end until the resume.
TEST(RunControlEnd, APauseNeverLandsOnARunThatIsEnding) {
  RunPlanView plan;
  plan.background = true;
  RunControl ending(nullptr);
  ending.begin(plan);
  EXPECT_TRUE(ending.finish_unless_paused());
  EXPECT_FALSE(ending.pause()) << "a pause after the last step would report a run that is about to end as paused";
  EXPECT_EQ(ending.state(), RunState::Running);
  ending.end(RunState::Finished, "t = 1 s");
  EXPECT_EQ(ending.state(), RunState::Finished);

  RunControl paused(nullptr);
  paused.begin(plan);
  EXPECT_TRUE(paused.pause());
  EXPECT_FALSE(paused.finish_unless_paused()) << "a run paused before its end must wait for the resume";
  EXPECT_TRUE(paused.resume());
  EXPECT_TRUE(paused.finish_unless_paused());

  RunControl held(nullptr);
  held.begin(plan);
  EXPECT_TRUE(held.finish_unless_paused());
  EXPECT_TRUE(held.hold_next()) << "the live view's Pause at a run's end holds the next run";
  held.end(RunState::Finished, "t = 1 s");
  held.begin(plan);
  EXPECT_EQ(held.state(), RunState::Paused);
}
