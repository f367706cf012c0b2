// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Runs that go on in the background while the console (or the rest of a
// script) stays up: m:start{...} (or m:run{..., background = true}),
// m:pause(), m:resume(), m:stop(), m:wait(), m:running(). The run steps on a
// thread of its own by the rules of run_control.hpp, the same steps as
// m:run (stepping.hpp), so a run paused and resumed ends bit for bit where a
// straight run ends.
#include <lua.hpp>

#include <thread>

#include "lua_support.hpp"
#include "stepping.hpp"

namespace dda::script {

class ScriptModel;

class BackgroundRun {
 public:
  // On the Lua thread, holding the model: starts the thread.
  BackgroundRun(lua_State* L, int model_idx, ScriptModel& m, RunPlan plan, long first_step);
  // Stops the run at its next step boundary and waits for its thread.
  ~BackgroundRun();
  BackgroundRun(const BackgroundRun&) = delete;
  BackgroundRun& operator=(const BackgroundRun&) = delete;

  // Once the run has ended: joins its thread and lets the model be
  // collected again (it is anchored while the run goes on).
  void collect_if_ended();

 private:
  void main();
  // Holding the model, with a step left: one step and its follow-up; false
  // when the run ends here (callback said stop, error: `failed` then holds
  // it).
  bool one_step(std::string& failed);

  ScriptModel& m_;
  LuaRef anchor_;      // the model's userdata, while the run goes on
  LuaRef lua_thread_;  // a Lua thread of the state: loads and callbacks run on it
  lua_State* lua_ = nullptr;
  Stepping run_;
  std::thread thread_;
};

// m:start{...} and m:run{..., background = true}: begins the run on the
// model at model_idx.
void start_background_run(lua_State* L, int model_idx, ScriptModel& m, RunPlan plan);

// m:start, m:pause, m:resume, m:stop, m:wait, m:running.
void register_background(lua_State* L);

}  // namespace dda::script
