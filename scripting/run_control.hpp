// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Who may touch a model, and when: the rules that let a run go on in the
// background while the console stays up, and a live view read it as it goes.
//
//  - A model is touched by one thread at a time, the one holding its
//    RunControl::lock: the stepping loop for each step, the Lua thread for
//    each API call on the model (check_model and check_handle take it; it is
//    held until that call returns), the live view while it copies a
//    snapshot. Between two steps each takes its turn in the order it asked
//    (TurnLock), so whatever one call reads is the state between two steps,
//    whole, and a reader waits at most one step.
//  - Lua runs on one thread at a time, the one holding lua_gate(): the Lua
//    thread while it runs a script or a console statement (not while the
//    console waits for input, nor in m:wait()), a background run for a step
//    whose loads are Lua functions or that calls its callback. Lua never
//    runs inside a step's parallel stages. The gate is always taken before a
//    model's lock, never after.
//  - While a background run is running, the Lua thread may read its model
//    but not change it (m:pause() first); paused, the model is the script's
//    to change, and m:resume() goes on from there.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "turn_lock.hpp"

namespace dda::script {

class ScriptModel;

enum class RunState { Idle, Running, Paused, Finished, Failed, Stopped };
const char* to_string(RunState s);

// What the live view shows of the run in progress: where it started and
// where it ends (−1: not by time / not by steps), its real-time pacing.
struct RunPlanView {
  double t_start = 0, t_end = -1;
  long step_start = 0, step_end = -1;
  double realtime = 0;  // simulated seconds per wall second asked for (0: as fast as it goes)
  bool background = false;
};

class RunControl {
 public:
  explicit RunControl(ScriptModel* model) : model_(model) {}
  RunControl(const RunControl&) = delete;
  RunControl& operator=(const RunControl&) = delete;

  TurnLock lock;  // held by whoever touches the model

  // The model, or nullptr once it is gone (read it holding `lock`).
  ScriptModel* model() const { return model_; }
  void forget_model();  // by ~ScriptModel, holding `lock`

  // ---- the stepping loop ----------------------------------------------------------
  // A run begins (state Running) and ends: a background run as Finished,
  // Failed (with the error) or Stopped; a foreground one back to Idle.
  // `summary` ("t = 0.5 s, step 1000") is what the console's notice says.
  void begin(const RunPlanView& plan);
  void end(RunState final_state, const std::string& summary, std::string error = {});
  // Between steps, holding nothing of the model: waits while paused and,
  // when `until` is given, until then (real-time pacing); wakes early when
  // paused, resumed or stopped. Whatever the calling thread holds (the
  // model, Lua) it lets go of while it waits and takes back after. Returns
  // false once the run is to stop (stop(), or `give_up` returning true:
  // Ctrl-C in the foreground, polled while paused).
  using Clock = std::chrono::steady_clock;
  bool wait_between_steps(const Clock::time_point* until, const std::function<bool()>& give_up = {});
  // The run has no step left: from now on pause() is refused, so a pause
  // that says "paused" never lands on a run about to end. Returns false
  // when the run was paused first: it then waits between steps as any
  // paused run does, and asks again once resumed.
  bool finish_unless_paused();
  // The run's real-time pacing: seconds behind the schedule it could not
  // keep (0 when it keeps up), as the live view shows it.
  void set_behind(double seconds);

  // ---- requests, from any thread ----------------------------------------------------------
  // pause: Running → Paused (no step begins after it returns; refused once
  // the run has no step left); resume:
  // Paused → Running; stop: the run ends at the next step boundary. Each
  // returns whether it changed anything.
  bool pause();
  bool resume();
  bool stop();
  // The live view's Pause: pause() a run in progress, or, between stepping
  // calls (a script that steps with m:step() in a loop), have the next run
  // begin paused; resume() lets it go.
  bool hold_next();

  // ---- state, from any thread ---------------------------------------------------------------
  RunState state() const;
  bool holding_next() const;  // hold_next() between runs, not yet resumed
  bool active() const;        // Running or Paused
  bool background() const;
  // Waits until the run has ended (no longer Running or Paused); gives up
  // when `give_up` returns true (called every 0.1 s, holding nothing of the
  // control). Returns whether it ended.
  bool wait_for_end(const std::function<bool()>& give_up = {});
  std::string error() const;
  RunPlanView plan() const;
  double behind() const;
  // The thread a background run steps on (callbacks may change the model
  // from there); none otherwise.
  std::thread::id stepping_thread() const;
  void set_stepping_thread(std::thread::id id);
  // Once: the line the console prints when a background run has ended
  // ("" when there is nothing new to say).
  std::string take_notice();

 private:
  ScriptModel* model_;
  mutable std::mutex m_;
  std::condition_variable cv_;
  RunState state_ = RunState::Idle;
  RunPlanView plan_;
  std::string error_;
  double behind_ = 0;
  bool stop_ = false;
  bool hold_next_ = false;
  bool finishing_ = false;  // finish_unless_paused() said yes: nothing left to pause
  std::string notice_;      // for take_notice (empty once taken)
  std::thread::id stepping_thread_;
};

// ---- the Lua thread's holds -------------------------------------------------------
// The lock of "who may run Lua now" (one per process).
TurnLock& lua_gate();

// The calling thread holds `m`'s model until the API call that asked
// returns (ApiCallScope, opened by every guarded call): it waits for a step
// in progress to end.
void hold_for_call(ScriptModel& m);

// A background run's thread says so once; calls from its callbacks then
// never let go of Lua (it holds its model meanwhile), and may not wait for
// or end their own run.
void mark_stepping_thread();
bool on_stepping_thread();

class ApiCallScope {
 public:
  ApiCallScope();
  ~ApiCallScope();  // lets go of the models this call took
  ApiCallScope(const ApiCallScope&) = delete;
  ApiCallScope& operator=(const ApiCallScope&) = delete;

 private:
  std::size_t mark_;
};

// For a blocking wait (m:wait(), the end of a batch run): lets go of every
// model the calling thread holds and of Lua; takes them back (Lua first)
// when it goes out of scope.
class LetGo {
 public:
  LetGo();
  ~LetGo();
  LetGo(const LetGo&) = delete;
  LetGo& operator=(const LetGo&) = delete;

 private:
  int gate_depth_ = 0;
  std::vector<std::pair<std::shared_ptr<RunControl>, int>> models_;
};

// Lets go of every hold an API call left behind (a Lua error that unwound
// past its scope): the console calls it after each statement.
void release_call_holds();

// ---- the process's background runs --------------------------------------------------
void register_background_run(const std::shared_ptr<RunControl>& c);
// Pauses every running background run; returns the lines saying which.
std::vector<std::string> pause_background_runs();
// The lines of background runs that ended since the last call.
std::vector<std::string> background_run_notices();
// The errors of background runs that failed ("background run failed at
// ...: why"), each said once (here or by background_run_notices).
std::vector<std::string> background_failures();
// Asks every background run to stop and waits until each has (holding
// nothing meanwhile): before the Lua state closes.
void stop_background_runs();
// Waits for every running background run to end (holding nothing
// meanwhile); a paused one is waited for only when `paused_too` (a live view
// can resume it). Returns early when `give_up` returns true.
void wait_background_runs(bool paused_too, const std::function<bool()>& give_up = {});

}  // namespace dda::script
