// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "run_control.hpp"

#include <algorithm>

#include "model.hpp"

namespace dda::script {

const char* to_string(RunState s) {
  switch (s) {
    case RunState::Idle:
      return "idle";
    case RunState::Running:
      return "running";
    case RunState::Paused:
      return "paused";
    case RunState::Finished:
      return "finished";
    case RunState::Failed:
      return "failed";
    case RunState::Stopped:
      return "stopped";
  }
  return "?";
}

void RunControl::forget_model() {
  std::lock_guard g(m_);
  model_ = nullptr;
}

void RunControl::begin(const RunPlanView& plan) {
  std::lock_guard g(m_);
  state_ = hold_next_ ? RunState::Paused : RunState::Running;
  hold_next_ = false;
  plan_ = plan;
  error_.clear();
  notice_.clear();
  behind_ = 0;
  stop_ = false;
  finishing_ = false;
  cv_.notify_all();
}

void RunControl::end(RunState final_state, const std::string& summary, std::string error) {
  std::lock_guard g(m_);
  const bool background = plan_.background;
  state_ = background ? final_state : RunState::Idle;
  error_ = std::move(error);
  if (background) {
    notice_ = final_state == RunState::Failed
                  ? "background run failed at " + summary + ": " + error_
                  : std::string("background run ") + to_string(final_state) + " at " + summary;
  }
  stepping_thread_ = std::thread::id();
  cv_.notify_all();
}

bool RunControl::wait_between_steps(const Clock::time_point* until, const std::function<bool()>& give_up) {
  std::unique_lock g(m_);
  auto waiting = [&] { return !stop_ && (state_ == RunState::Paused || (until && Clock::now() < *until)); };
  if (!waiting()) return !stop_;
  // Let go of the model and of Lua while waiting (a foreground run holds
  // both; a background one neither).
  g.unlock();
  const int model_depth = lock.release_all();
  const int gate_depth = lua_gate().release_all();
  bool gave_up = false;
  g.lock();
  while (waiting()) {
    auto wake = Clock::now() + std::chrono::milliseconds(100);
    if (until && state_ != RunState::Paused) wake = std::min(wake, *until);
    cv_.wait_until(g, wake);
    if (give_up) {
      g.unlock();
      gave_up = give_up();
      g.lock();
      if (gave_up) break;
    }
  }
  const bool go_on = !stop_ && !gave_up;
  g.unlock();
  lua_gate().take_back(gate_depth);
  lock.take_back(model_depth);
  return go_on;
}

bool RunControl::finish_unless_paused() {
  std::lock_guard g(m_);
  if (state_ == RunState::Paused) return false;
  finishing_ = true;
  return true;
}

void RunControl::set_behind(double seconds) {
  std::lock_guard g(m_);
  behind_ = seconds;
}

bool RunControl::pause() {
  std::lock_guard g(m_);
  if (state_ != RunState::Running || finishing_) return false;
  state_ = RunState::Paused;
  cv_.notify_all();
  return true;
}

bool RunControl::hold_next() {
  std::lock_guard g(m_);
  if (state_ == RunState::Paused || hold_next_) return false;
  if (state_ == RunState::Running && !finishing_)
    state_ = RunState::Paused;
  else
    hold_next_ = true;
  cv_.notify_all();
  return true;
}

bool RunControl::resume() {
  std::lock_guard g(m_);
  if (hold_next_) {
    hold_next_ = false;
    return true;
  }
  if (state_ != RunState::Paused) return false;
  state_ = RunState::Running;
  cv_.notify_all();
  return true;
}

bool RunControl::stop() {
  std::lock_guard g(m_);
  if (state_ != RunState::Running && state_ != RunState::Paused) return false;
  stop_ = true;
  cv_.notify_all();
  return true;
}

RunState RunControl::state() const {
  std::lock_guard g(m_);
  return state_;
}

bool RunControl::holding_next() const {
  std::lock_guard g(m_);
  return hold_next_;
}

bool RunControl::active() const {
  const RunState s = state();
  return s == RunState::Running || s == RunState::Paused;
}

bool RunControl::background() const {
  std::lock_guard g(m_);
  return plan_.background;
}

bool RunControl::wait_for_end(const std::function<bool()>& give_up) {
  for (;;) {
    {
      std::unique_lock g(m_);
      cv_.wait_for(g, std::chrono::milliseconds(100),
                   [&] { return state_ != RunState::Running && state_ != RunState::Paused; });
      if (state_ != RunState::Running && state_ != RunState::Paused) return true;
    }
    if (give_up && give_up()) return false;
  }
}

std::string RunControl::error() const {
  std::lock_guard g(m_);
  return error_;
}

RunPlanView RunControl::plan() const {
  std::lock_guard g(m_);
  return plan_;
}

double RunControl::behind() const {
  std::lock_guard g(m_);
  return behind_;
}

std::thread::id RunControl::stepping_thread() const {
  std::lock_guard g(m_);
  return stepping_thread_;
}

void RunControl::set_stepping_thread(std::thread::id id) {
  std::lock_guard g(m_);
  stepping_thread_ = id;
}

std::string RunControl::take_notice() {
  std::lock_guard g(m_);
  std::string n;
  n.swap(notice_);
  return n;
}

// ---- holds -----------------------------------------------------------------------------

TurnLock& lua_gate() {
  static TurnLock gate;
  return gate;
}

namespace {
// The models the calling thread's API calls hold, innermost last.
thread_local std::vector<std::shared_ptr<RunControl>> t_held;
// Whether this thread steps a background run (it holds its model, and Lua
// for its callbacks, from outside any API call).
thread_local bool t_stepping = false;
}  // namespace

void mark_stepping_thread() { t_stepping = true; }

bool on_stepping_thread() { return t_stepping; }

void hold_for_call(ScriptModel& m) {
  const std::shared_ptr<RunControl>& c = m.shared_control();
  for (const auto& h : t_held)
    if (h == c) return;
  // A call that holds no model yet is where the Lua thread lets a
  // background run that waits for Lua take its step (as Lua itself lets
  // other threads in around C calls): a script that polls m:running() or
  // m:time() in a loop sees the run go on.
  if (t_held.empty() && !t_stepping && lua_gate().held_by_this_thread()) lua_gate().yield();
  c->lock.lock();
  t_held.push_back(c);
}

ApiCallScope::ApiCallScope() : mark_(t_held.size()) {}

ApiCallScope::~ApiCallScope() {
  while (t_held.size() > mark_) {
    t_held.back()->lock.unlock();
    t_held.pop_back();
  }
}

void release_call_holds() {
  while (!t_held.empty()) {
    t_held.back()->lock.release_all();
    t_held.pop_back();
  }
}

LetGo::LetGo() {
  for (const auto& h : t_held) models_.emplace_back(h, h->lock.release_all());
  gate_depth_ = lua_gate().release_all();
}

LetGo::~LetGo() {
  lua_gate().take_back(gate_depth_);
  for (auto& [c, depth] : models_) c->lock.take_back(depth);
}

// ---- the process's background runs -----------------------------------------------------------

namespace {
std::mutex g_runs_mutex;
std::vector<std::weak_ptr<RunControl>> g_runs;

std::vector<std::shared_ptr<RunControl>> runs() {
  std::lock_guard g(g_runs_mutex);
  std::vector<std::shared_ptr<RunControl>> out;
  std::erase_if(g_runs, [](const std::weak_ptr<RunControl>& w) { return w.expired(); });
  for (const auto& w : g_runs)
    if (auto c = w.lock()) out.push_back(std::move(c));
  return out;
}
}  // namespace

void register_background_run(const std::shared_ptr<RunControl>& c) {
  std::lock_guard g(g_runs_mutex);
  for (const auto& w : g_runs)
    if (w.lock() == c) return;
  g_runs.push_back(c);
}

std::vector<std::string> pause_background_runs() {
  std::vector<std::string> lines;
  for (const auto& c : runs())
    if (c->background() && c->pause()) lines.push_back("background run paused (m:resume() goes on)");
  return lines;
}

std::vector<std::string> background_run_notices() {
  std::vector<std::string> lines;
  for (const auto& c : runs())
    if (std::string n = c->take_notice(); !n.empty()) lines.push_back(std::move(n));
  return lines;
}

std::vector<std::string> background_failures() {
  std::vector<std::string> lines;
  for (const auto& c : runs())
    if (c->background() && c->state() == RunState::Failed)
      if (std::string n = c->take_notice(); !n.empty()) lines.push_back(std::move(n));
  return lines;
}

void stop_background_runs() {
  const auto all = runs();
  LetGo let_go;
  for (const auto& c : all)
    if (c->background()) c->stop();
  for (const auto& c : all)
    if (c->background()) c->wait_for_end();
}

void wait_background_runs(bool paused_too, const std::function<bool()>& give_up) {
  const auto all = runs();
  LetGo let_go;
  for (const auto& c : all) {
    if (!c->background()) continue;
    if (!paused_too && c->state() == RunState::Paused) continue;
    if (!c->wait_for_end(give_up)) return;
  }
}

}  // namespace dda::script
