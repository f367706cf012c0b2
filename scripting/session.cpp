// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "session.hpp"

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <mutex>
#include <new>
#include <system_error>

#include "lua_support.hpp"

namespace dda::script {

namespace {

const char kSessionKey = 0;  // its address keys the session in the registry

int session_gc(lua_State* L) {
  static_cast<Session*>(lua_touserdata(L, 1))->~Session();
  return 0;
}

Session* find_session(lua_State* L) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kSessionKey);
  auto* s = static_cast<Session*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  return s;
}

Session* new_session(lua_State* L, Session value) {
  void* mem = lua_newuserdatauv(L, sizeof(Session), 0);
  auto* s = new (mem) Session(std::move(value));
  lua_createtable(L, 0, 1);
  lua_pushcfunction(L, session_gc);
  lua_setfield(L, -2, "__gc");
  lua_setmetatable(L, -2);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kSessionKey);
  return s;
}

volatile std::sig_atomic_t g_interrupted = 0;
lua_State* g_state = nullptr;

void stop_hook(lua_State* L, lua_Debug*) {
  lua_sethook(L, nullptr, 0, 0);
  luaL_error(L, "interrupted!");
}

// SIGINT (Ctrl-C) and SIGTERM (what a batch queue sends first, before
// SIGKILL): the same stop at the next step boundary.
extern "C" void on_stop_signal(int sig) {
  std::signal(sig, SIG_DFL);  // a second one terminates the process
  g_interrupted = sig;
  if (g_state) lua_sethook(g_state, stop_hook, LUA_MASKCALL | LUA_MASKRET | LUA_MASKCOUNT, 1);
}

}  // namespace

Session& session(lua_State* L) {
  if (Session* s = find_session(L)) return *s;
  return *new_session(L, Session{});
}

void set_session(lua_State* L, Session s) {
  if (Session* old = find_session(L)) {
    *old = std::move(s);
    return;
  }
  new_session(L, std::move(s));
}

void install_interrupt_handler(lua_State* L) {
  lua_rawgeti(L, LUA_REGISTRYINDEX, LUA_RIDX_MAINTHREAD);
  g_state = lua_tothread(L, -1);
  lua_pop(L, 1);
  g_interrupted = 0;
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
}

void remove_interrupt_handler() {
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (g_state) lua_sethook(g_state, nullptr, 0, 0);
  g_state = nullptr;
}

bool interrupt_requested() { return g_interrupted != 0; }

int interrupt_signal() { return g_interrupted; }

const char* interrupt_name() { return g_interrupted == SIGTERM ? "terminated (SIGTERM)" : "interrupted (Ctrl-C)"; }

void clear_interrupt() { g_interrupted = 0; }

void check_interrupt(const char* where_text) {
  if (!g_interrupted) return;
  // The hook has done its job (we stop here, at a step boundary); clear it so
  // it does not fire again inside the error handler.
  if (g_state) lua_sethook(g_state, nullptr, 0, 0);
  throw Interrupted(msg(interrupt_name(), " ", where_text));
}

void stop_if_params_only(lua_State* L, const char* what) {
  Session& s = session(L);
  if (!s.params_only) return;
  s.params_stopped = true;
  throw ParamsOnlyStop(msg("--list-params: stopped at ", what));
}

// ---- run log --------------------------------------------------------------------------

void RunLog::open(const std::filesystem::path& path) {
  close();
  path_ = path;
  failure_.clear();
  std::error_code ec;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
  try {
    file_ = AppendFile(path, AppendFile::Mode::Append);
  } catch (const std::exception& e) {
    failed(e.what());
  }
}

void RunLog::failed(const std::string& why) {
  std::fprintf(stderr, "dda: warning: run log: %s; the run goes on without it\n", why.c_str());
  if (failure_.empty()) failure_ = why;
  file_ = AppendFile();
}

void RunLog::line(const std::string& text) {
  static std::mutex mutex;  // warnings come from background runs' threads too
  std::lock_guard g(mutex);
  if (!file_.is_open()) return;
  char stamp[32];
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  localtime_r(&now, &tm);
  std::strftime(stamp, sizeof stamp, "%Y-%m-%d %H:%M:%S", &tm);
  try {
    file_.append(std::string(stamp) + "  " + text + "\n");
  } catch (const std::exception& e) {
    failed(e.what());
  }
}

void RunLog::close() {
  try {
    file_.close();
  } catch (const std::exception& e) {
    failed(e.what());
  }
}

namespace {
RunLog* g_run_log = nullptr;
}  // namespace

void set_run_log(RunLog* log) { g_run_log = log; }

void warn(const std::string& text) {
  static std::mutex mutex;
  std::lock_guard g(mutex);
  std::fprintf(stderr, "dda: warning: %s\n", text.c_str());
  std::fflush(stderr);
  if (g_run_log) g_run_log->line("warning: " + text);
}

// ---- progress -----------------------------------------------------------------------

Progress::Progress(lua_State* L, double t_start, double t_end, long step_start, long step_end)
    : mode_(session(L).progress),
      line_seconds_(session(L).progress_seconds),
      t_start_(t_start),
      t_end_(t_end),
      step_start_(step_start),
      step_end_(step_end),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

Progress::~Progress() {
  if (drawn_) {
    std::fputs("\r\033[K", stderr);
    std::fflush(stderr);
  }
}

void Progress::update(double t, long step) {
  if (mode_ == ProgressMode::None) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double since = std::chrono::duration<double>(now - last_).count();
  const long done = step - step_start_;
  double fraction = -1;
  if (t_end_ > t_start_) fraction = (t - t_start_) / (t_end_ - t_start_);
  if (step_end_ > step_start_) fraction = std::max(fraction, double(done) / double(step_end_ - step_start_));
  if (mode_ == ProgressMode::Lines) {
    // A 5 % mark (at most one line a second), or line_seconds_ since the last line.
    constexpr double kSlack = 1e-9;  // t accumulates Δt: 0.05 may come out as 0.0499999...
    const bool mark = fraction >= next_fraction_ - kSlack && (since >= 1 || line_seconds_ <= 0);
    const bool timed = line_seconds_ > 0 && since >= line_seconds_;
    if (!mark && !timed) return;
    last_ = now;
    while (fraction >= next_fraction_ - kSlack) next_fraction_ += 0.05;
    std::fprintf(stderr, "progress: %s\n", text(t, step, elapsed, fraction).c_str());
    std::fflush(stderr);
    return;
  }
  if (elapsed < 0.5 || since < 0.2) return;
  last_ = now;
  std::fprintf(stderr, "\r\033[K%s", text(t, step, elapsed, fraction).c_str());
  std::fflush(stderr);
  drawn_ = true;
}

std::string Progress::text(double t, long step, double elapsed, double fraction) const {
  const long done = step - step_start_;
  const double rate = elapsed > 0 ? done / elapsed : 0;
  char eta[64] = "";
  if (fraction > 0 && fraction <= 1) {
    const double left = elapsed * (1 - fraction) / fraction;
    if (left >= 3600)
      std::snprintf(eta, sizeof eta, " | ETA %dh%02dm", int(left / 3600), int(left / 60) % 60);
    else if (left >= 60)
      std::snprintf(eta, sizeof eta, " | ETA %dm%02ds", int(left / 60), int(left) % 60);
    else
      std::snprintf(eta, sizeof eta, " | ETA %.0f s", left);
  }
  char target[64] = "";
  if (t_end_ > t_start_) std::snprintf(target, sizeof target, " / %.4g s", t_end_);
  if (mode_ == ProgressMode::Lines && fraction >= 0)
    std::snprintf(target + std::strlen(target), sizeof target - std::strlen(target), " (%.0f %%)",
                  100 * std::min(fraction, 1.0));
  char line[256];
  std::snprintf(line, sizeof line, "t = %.4g s%s | step %ld | %.0f steps/s%s", t, target, step, rate, eta);
  return line;
}

}  // namespace dda::script
