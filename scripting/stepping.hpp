// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// One stepping call's run, step by step: what m:step, m:run_until and m:run
// do on the Lua thread and m:start does on its own thread. The same steps
// either way, so a run paused and resumed, or run in the background, ends
// bit for bit where the same run in one go ends.
//
//   Stepping run(L, 1, m, plan, first_step);  // on the Lua thread, holding the model
//   while (!run.done()) {                     // between steps
//     run.advance(L);                         // holding the model (and Lua when run.needs_lua())
//     if (!run.follow_up(L)) break;           // the callback asked to stop
//   }
#include <lua.hpp>

#include <chrono>
#include <filesystem>
#include <string>

#include "lua_support.hpp"
#include "run_control.hpp"

namespace dda::script {

class ScriptModel;

struct RunPlan {
  double t_end = -1;    // run until time ≥ t_end (when ≥ 0)
  long steps = -1;      // or this many steps (when ≥ 0)
  long every = 1;       // call the callback every N steps
  LuaRef callback;      // called with the model after every `every` steps; false stops the run
  double realtime = 0;  // > 0: simulated seconds per wall-clock second (paced); 0: as fast as it goes
};

// --checkpoint-every N | Ts, as the session had it when the run began.
struct CheckpointPolicy {
  long steps = 0;
  double seconds = 0;
  std::filesystem::path path;
};

class Stepping {
 public:
  using Clock = std::chrono::steady_clock;

  // On the Lua thread, before the first step. `first_step`: the step count
  // the plan's steps count from; `model_idx`: the model's userdata (for the
  // callback).
  Stepping(lua_State* L, int model_idx, ScriptModel& m, RunPlan plan, long first_step);

  // Between steps: whether the plan is complete.
  bool done() const;
  // Whether the next step runs Lua (loads that are Lua functions, the
  // callback): the caller must hold lua_gate() for it.
  bool needs_lua() const;
  // One step (L: the Lua state of this thread, for loads that are Lua
  // functions); then its callback when due and a checkpoint when due,
  // returning false when the callback asked to stop.
  void advance(lua_State* L);
  bool follow_up(lua_State* L);
  // A checkpoint now (Ctrl-C), when the run writes them.
  void checkpoint_now();

  // Real-time pacing: the wall-clock time the next step may begin, or
  // nullptr (not paced). Re-anchors the schedule when the run fell behind
  // it (it never races to catch up) and tells the RunControl by how much.
  const Clock::time_point* next_start();
  // The run's pace so far in simulated seconds per wall second, and the
  // line saying it could not keep to its real-time factor ("" when it kept
  // to it, or was not paced).
  double pace() const;
  std::string pace_report() const;
  // "t = 0 → 0.003 s, 1500 steps in 5.9 s of wall clock: 0.00051 s of
  // simulated time per second" (the run log's line for each stepping call).
  std::string summary() const;
  // First call after the run fell more than half a second behind: the line
  // to warn with (once per run); "" otherwise.
  std::string take_lag_warning();

  // After a restart the model may stand ahead of the script: it stands
  // where this call ended in the straight run (known only for a count of
  // steps).
  void settle_replay_mark();

  RunPlanView view(bool background) const;
  const RunPlan& plan() const { return plan_; }
  long first_step() const { return s0_; }
  // "t = 0.0012 s, step 600"
  std::string where() const;

 private:
  void checkpoint_if_due(bool now);

  ScriptModel& m_;
  RunPlan plan_;
  LuaRef model_ref_;  // for the callback
  CheckpointPolicy checkpoints_;
  long s0_ = 0;
  double t0_ = 0;
  Clock::time_point wall0_;
  double schedule_t0_ = 0;           // the simulated time the schedule is anchored at
  Clock::time_point schedule_wall_;  // ... and its wall-clock time
  Clock::time_point next_;
  double behind_total_ = 0;  // s the schedule was moved on by
  bool warned_lag_ = false;
  bool lag_pending_ = false;
};

// What every stepping call does first, on the Lua thread (wrap_model.cpp):
// a pending --restart takes the checkpoint's state, Ctrl-C already pressed
// stops it, the run log gets the controls, and the model's first call
// decides its wave model over the span `plan` asks for. Returns the step
// count the call's steps count from.
long begin_stepping_call(lua_State* L, ScriptModel& m, const RunPlan& plan);

// The plan of m:run{...} / m:start{...} from its options (time, steps,
// every, callback, realtime: run_plan_options()) (wrap_model.cpp).
RunPlan read_run_plan(const Options& o);
Names run_plan_options();

// The checkpoint file of model number `model` in the output folder.
std::filesystem::path periodic_checkpoint_path(const std::filesystem::path& out_dir, int model);

}  // namespace dda::script
