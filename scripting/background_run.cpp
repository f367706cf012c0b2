// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "background_run.hpp"

#include <chrono>

#include "model.hpp"
#include "session.hpp"
#include "wrap.hpp"

namespace dda::script {

BackgroundRun::BackgroundRun(lua_State* L, int model_idx, ScriptModel& m, RunPlan plan, long first_step)
    : m_(m), anchor_(L, model_idx), run_(L, model_idx, m, std::move(plan), first_step) {
  lua_ = lua_newthread(L);
  lua_thread_ = LuaRef(L, -1);
  lua_pop(L, 1);
  RunControl& c = m_.control();
  c.begin(run_.view(true));
  register_background_run(m_.shared_control());
  thread_ = std::thread([this] { main(); });
}

BackgroundRun::~BackgroundRun() {
  m_.control().stop();
  if (thread_.joinable()) {
    LetGo let_go;  // the run may wait for the model or for Lua to end its step
    thread_.join();
  }
}

void BackgroundRun::collect_if_ended() {
  if (m_.control().active()) return;
  if (thread_.joinable()) {
    LetGo let_go;
    thread_.join();
  }
  anchor_.reset();
}

bool BackgroundRun::one_step(std::string& failed) {
  try {
    run_.advance(lua_);
    return run_.follow_up(lua_);
  } catch (const std::exception& e) {
    failed = e.what();  // (a LuaCallError lets go of its Lua value here, Lua still held)
    return false;
  }
}

void BackgroundRun::main() {
  RunControl& c = m_.control();
  c.set_stepping_thread(std::this_thread::get_id());
  mark_stepping_thread();
  RunState final_state = RunState::Finished;
  std::string failed, summary;
  for (;;) {
    if (!c.wait_between_steps(run_.next_start())) {
      final_state = RunState::Stopped;
      c.lock.lock();
      summary = run_.where();
      c.lock.unlock();
      break;
    }
    // Lua before the model (run_control.hpp); Lua only for a step that runs it.
    c.lock.lock();
    const bool lua = run_.needs_lua();
    if (lua) {
      c.lock.unlock();
      lua_gate().lock();
      c.lock.lock();
    }
    bool go_on = true;
    if (run_.done())
      go_on = !c.finish_unless_paused();  // (paused just as it came to its end: wait for the resume)
    else if (c.state() == RunState::Running)
      go_on = one_step(failed);  // (else paused while it waited)
    if (!go_on) {
      if (!failed.empty()) final_state = RunState::Failed;
      run_.settle_replay_mark();
      summary = run_.where();
    }
    c.lock.unlock();
    if (lua) lua_gate().unlock();
    if (!go_on) break;
  }
  if (const std::string pace = run_.pace_report(); !pace.empty()) summary += "; " + pace;
  c.end(final_state, summary, failed);
}

void start_background_run(lua_State* L, int model_idx, ScriptModel& m, RunPlan plan) {
  const long s0 = begin_stepping_call(L, m, plan);
  m.background.reset();  // the last one's end, collected
  m.background = std::make_unique<BackgroundRun>(L, model_idx, m, std::move(plan), s0);
}

namespace {

// A callback of a background run cannot wait for, stop or close its own run.
void refuse_on_stepping_thread(const char* call) {
  if (on_stepping_thread()) fail(call, ": not from a callback of a background run (it would wait for itself)");
}

int push_time_and_step(lua_State* L, ScriptModel& m) {
  lua_pushnumber(L, m.world().time());
  lua_pushinteger(L, m.world().step_count());
  return 2;
}

// m:start{time = t | steps = n, every = N, callback = f, realtime = r}
int m_start(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:start");
  check_not_busy(m, "m:start");
  if (m.control().active())
    fail("m:start: the model has a run in progress (", to_string(m.control().state()),
         "): m:wait() for its end, or m:stop() it first");
  const Options o(L, 2, "m:start", run_plan_options());
  start_background_run(L, 1, m, read_run_plan(o));
  return 0;
}

// m:pause() → t, step, paused: no step begins after it returns; paused is
// whether a run is paused now (false: none was going, or it had taken its
// last step).
int m_pause(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:pause");
  RunControl& c = m.control();
  if (c.background()) c.pause();
  push_time_and_step(L, m);
  lua_pushboolean(L, c.background() && c.state() == RunState::Paused);
  return 3;
}

// m:resume() → whether a paused background run goes on now.
int m_resume(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:resume");
  lua_pushboolean(L, m.control().background() && m.control().resume());
  return 1;
}

// m:stop() → t, step: the background run ends at its next step boundary.
int m_stop(lua_State* L) {
  refuse_on_stepping_thread("m:stop");
  ScriptModel& m = check_model(L, 1, "m:stop");
  if (m.background) {
    if (m.control().stop()) {
      LetGo let_go;  // the run may be waiting for its turn at the model
      m.control().wait_for_end();
    }
    m.background->collect_if_ended();
  }
  return push_time_and_step(L, m);
}

// m:wait() → t, step: waits for the background run to end; raises its error.
// Ctrl-C pauses it and stops the wait.
int m_wait(lua_State* L) {
  refuse_on_stepping_thread("m:wait");
  ScriptModel& m = check_model(L, 1, "m:wait");
  RunControl& c = m.control();
  if (c.state() == RunState::Paused) fail("m:wait: the background run is paused: m:resume() it first (or m:stop() it)");
  if (c.active()) {
    const RunPlanView plan = c.plan();
    Progress progress(L, plan.t_start, plan.t_end >= 0 ? plan.t_end : 0, plan.step_start,
                      plan.step_end >= 0 ? plan.step_end : 0);
    LetGo let_go;  // the run takes its turns at the model, and at Lua for its loads
    const bool ended = c.wait_for_end([&] {
      if (interrupt_requested()) return true;
      std::lock_guard hold(c.lock);
      progress.update(m.world().time(), m.world().step_count());
      return false;
    });
    if (!ended) {
      c.pause();
      std::string where;
      {
        std::lock_guard hold(c.lock);
        where = msg("in m:wait(): the background run is paused at step ", m.world().step_count(),
                    ", t = ", m.world().time(), " s; m:resume() goes on");
      }
      check_interrupt(where.c_str());  // (clears the Ctrl-C hook, then throws)
    }
  }
  if (m.background) m.background->collect_if_ended();
  if (c.state() == RunState::Failed) fail("m:wait: the background run failed: ", c.error());
  return push_time_and_step(L, m);
}

// m:running() → boolean, state: whether a background run is running, and
// "running", "paused", "finished", "failed", "stopped" or "idle".
int m_running(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:running");
  if (m.background) m.background->collect_if_ended();
  const RunState s = m.control().background() ? m.control().state() : RunState::Idle;
  lua_pushboolean(L, s == RunState::Running);
  lua_pushstring(L, to_string(s));
  return 2;
}

}  // namespace

void register_background(lua_State* L) {
  static const Method methods[] = {
      {"start", guarded<m_start>,
       "m:start{...}\nThe run of m:run{...} on a thread of its own; the console stays up. While it runs the model "
       "can be read (each call sees it between two steps) but not changed: m:pause() first.",
       run_plan_options()},
      {"pause", guarded<m_pause>,
       "m:pause() → t, step, paused\nPauses the background run: no step begins after it returns (paused: false "
       "when none was going or it had taken its last step); loads, boundaries, controls and outputs can then be "
       "changed."},
      {"resume", guarded<m_resume>, "m:resume() → boolean\nWhether the paused background run goes on now."},
      {"stop", guarded<m_stop>, "m:stop() → t, step\nEnds the background run at its next step boundary."},
      {"wait", guarded<m_wait>,
       "m:wait() → t, step\nWaits for the background run to end (raises its error); Ctrl-C pauses it and stops "
       "the wait."},
      {"running", guarded<m_running>,
       "m:running() → boolean, state\nWhether a background run is running; state is \"running\", \"paused\", "
       "\"finished\", \"failed\", \"stopped\" or \"idle\"."},
      {}};
  add_model_methods(L, methods, "Background runs");
}

}  // namespace dda::script
