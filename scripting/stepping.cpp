// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "stepping.hpp"

#include <cmath>
#include <cstdio>
#include <system_error>

#include "model.hpp"
#include "session.hpp"

namespace dda::script {

std::filesystem::path periodic_checkpoint_path(const std::filesystem::path& out_dir, int model) {
  return out_dir / (model <= 1 ? std::string("checkpoint.ckpt") : msg("checkpoint_", model, ".ckpt"));
}

Stepping::Stepping(lua_State* L, int model_idx, ScriptModel& m, RunPlan plan, long first_step)
    : m_(m), plan_(std::move(plan)), s0_(first_step) {
  const Session& s = session(L);
  m_.threads_override = s.threads;
  if (plan_.realtime == 0) plan_.realtime = s.realtime;
  if (plan_.callback.valid()) model_ref_ = LuaRef(L, model_idx);
  checkpoints_ = {s.checkpoint_steps, s.checkpoint_seconds, periodic_checkpoint_path(s.out_dir, m_.number)};
  t0_ = schedule_t0_ = m_.world().time();
  wall0_ = schedule_wall_ = next_ = Clock::now();
}

bool Stepping::done() const {
  const World& w = m_.world();
  if (plan_.steps >= 0 && w.step_count() - s0_ >= plan_.steps) return true;
  if (plan_.t_end >= 0) {
    // Stop once t reaches t_end (within a millionth of a step: t accumulates Δt).
    const double slack = 1e-6 * (w.current_dt() > 0 ? w.current_dt() : 0);
    if (w.time() >= plan_.t_end - slack) return true;
  }
  return false;
}

bool Stepping::needs_lua() const { return plan_.callback.valid() || m_.loads_call_lua(); }

void Stepping::advance(lua_State* L) { m_.step(L); }

bool Stepping::follow_up(lua_State* L) {
  const long done = m_.world().step_count() - s0_;
  if (plan_.callback.valid() && done % plan_.every == 0) {
    plan_.callback.push(L);
    model_ref_.push(L);
    pcall(L, 1, 1);
    const bool stop = lua_type(L, -1) == LUA_TBOOLEAN && !lua_toboolean(L, -1);
    lua_pop(L, 1);
    if (stop) return false;
    if (m_.closed()) fail("m:run: the callback closed the model");
  }
  checkpoint_if_due(false);
  return true;
}

void Stepping::checkpoint_now() { checkpoint_if_due(true); }

// --checkpoint-every N | Ts: after a step (and its callback) when due, or
// `now` (Ctrl-C). The file is replaced atomically: the last one stays whole
// whatever happens to the next.
void Stepping::checkpoint_if_due(bool now) {
  const CheckpointPolicy& p = checkpoints_;
  if (p.steps <= 0 && p.seconds <= 0) return;
  const World& w = m_.world();
  const bool due = now || (p.steps > 0 && w.step_count() % p.steps == 0) ||
                   (p.seconds > 0 && w.time() >= m_.last_checkpoint_time + p.seconds);
  if (!due) return;
  std::error_code ec;
  std::filesystem::create_directories(p.path.parent_path(), ec);
  m_.save(p.path);
  m_.last_checkpoint_time = w.time();
}

const Stepping::Clock::time_point* Stepping::next_start() {
  if (!(plan_.realtime > 0)) return nullptr;
  const double t = m_.world().time();
  const auto due = schedule_wall_ + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>((t - schedule_t0_) / plan_.realtime));
  const auto now = Clock::now();
  // Behind by more than a frame's worth (20 ms): the schedule moves on from
  // here instead of racing to catch up; the live view shows the lag.
  const double late = std::chrono::duration<double>(now - due).count();
  if (late > 0.02) {
    behind_total_ += late;
    schedule_t0_ = t;
    schedule_wall_ = now;
    next_ = now;
    m_.control().set_behind(late);
    if (behind_total_ > 0.5 && !warned_lag_) lag_pending_ = warned_lag_ = true;
    return &next_;
  }
  m_.control().set_behind(0);
  next_ = due;
  return &next_;
}

namespace {
std::string three_digits(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}
}  // namespace

double Stepping::pace() const {
  const double wall = std::chrono::duration<double>(Clock::now() - wall0_).count();
  return wall > 0 ? (m_.world().time() - t0_) / wall : 0;
}

std::string Stepping::pace_report() const {
  if (!(plan_.realtime > 0)) return "";
  const double p = pace();
  // Within 5 % of the pace asked for (sleeps overshoot by a little).
  if (p >= 0.95 * plan_.realtime) return "";
  return msg("realtime = ", plan_.realtime, ": could not keep up: ", three_digits(p),
             " s of simulated time per second (", three_digits(p / plan_.realtime), " of the pace asked for)");
}

std::string Stepping::summary() const {
  const double wall = std::chrono::duration<double>(Clock::now() - wall0_).count();
  return msg("t = ", t0_, " -> ", m_.world().time(), " s, ", m_.world().step_count() - s0_, " steps in ", wall,
             " s of wall clock: ", pace(), " s of simulated time per second");
}

std::string Stepping::take_lag_warning() {
  if (!lag_pending_) return "";
  lag_pending_ = false;
  return msg("realtime = ", plan_.realtime, ": the run cannot keep up (", three_digits(pace()),
             " s of simulated time per second so far); it goes on as fast as it can");
}

void Stepping::settle_replay_mark() {
  if (!m_.replay_mark) return;
  const long end_step = s0_ + plan_.steps;
  m_.replay_mark =
      plan_.steps >= 0 && m_.world().step_count() > end_step ? std::optional<long>(end_step) : std::nullopt;
}

RunPlanView Stepping::view(bool background) const {
  RunPlanView v;
  v.t_start = t0_;
  v.t_end = plan_.t_end;
  v.step_start = s0_;
  v.step_end = plan_.steps >= 0 ? s0_ + plan_.steps : -1;
  v.realtime = plan_.realtime;
  v.background = background;
  return v;
}

std::string Stepping::where() const { return msg("t = ", m_.world().time(), " s, step ", m_.world().step_count()); }

}  // namespace dda::script
