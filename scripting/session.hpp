// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// What a script run shares across every model it builds: the output folder,
// the --set parameters, the --threads override, whether to draw a progress
// line, and the Ctrl-C flag. One Session lives in each lua_State's registry
// (a default one is created on first use, e.g. when a test opens the module
// directly).
#include <lua.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/output_file.hpp"

namespace dda::script {

using dda::AppendFile;
class ScriptModel;
class LiveServer;

// How stepping calls show their progress: a redrawn line on a terminal,
// plain lines (at most one every `progress_seconds`, and one per 5 % done)
// when the output goes to a file or a pipe (CI, nohup, a batch queue).
enum class ProgressMode { None, Bar, Lines };

// The run log beside the outputs (<out>/run.log): command line, version,
// threads, parameters, each model's controls, warnings, start and end, exit
// status. Appended to, one block per run, each line written whole
// (AppendFile). A log that cannot be written is reported at once and then
// left off, so it never stops a run; failure() keeps the cause, and `dda run`
// ends with exit status 1 naming it.
class RunLog {
 public:
  RunLog() = default;
  // A copy is closed (the file stays with the original): Session is copied
  // from the command-line options before any log is opened.
  RunLog(const RunLog& o) : path_(o.path_) {}
  RunLog& operator=(const RunLog& o) {
    if (this != &o) close(), path_ = o.path_;
    return *this;
  }
  RunLog(RunLog&& o) noexcept = default;
  RunLog& operator=(RunLog&& o) noexcept = default;
  ~RunLog() = default;
  void open(const std::filesystem::path& path);
  bool is_open() const { return file_.is_open(); }
  const std::filesystem::path& path() const { return path_; }
  void line(const std::string& text);  // "2026-11-25 02:50:01  text"
  void close();
  // "cannot write 'PATH': cause" once the log failed, else empty.
  const std::string& failure() const { return failure_; }

 private:
  void failed(const std::string& why);
  AppendFile file_;
  std::filesystem::path path_;
  std::string failure_;
};

// A value a script returns for the batch table (return {ppv = ...} or dda.result{...}).
struct ResultValue {
  std::string text;  // as written in the summary CSV
  bool number = false;
};

struct Session {
  std::filesystem::path out_dir = "out";
  std::map<std::string, std::string> params;       // --set NAME=VALUE
  std::map<std::string, std::string> params_read;  // names the script asked for → their defaults, as text
  // dda run --list-params: the script runs up to its first stepping call, or
  // the first file it would write or command it would run, and stops there
  // (params_stopped then says so): what it read by then is what it reads.
  bool params_only = false;
  bool params_stopped = false;
  int threads = -1;                            // --threads N (−1: leave to the script)
  bool quiet = false;                          // --quiet
  ProgressMode progress = ProgressMode::None;  // how stepping shows progress (see ProgressMode)
  double progress_seconds = 10;                // Lines: at most one line this often (plus one per 5 %)
  std::set<std::string> files;                 // CSV files opened in this run (no two monitors share one)
  std::string script;                          // the script being run (for messages)
  // --frames N [--frame-field F] [--frame-size WxH]: every model the script
  // creates writes a frame every N steps into <out>/frames (frames_2, ... for
  // later models). 0: none.
  long frames_every = 0;
  std::string frames_field = "sigma_yy";  // as m:frame{} (render::FrameOptions)
  int frames_width = 1280, frames_height = 720;
  long frames_from = 0, frames_to = -1;  // --frames FROM:TO:EVERY (steps; -1: no end)
  bool frames_range_set = false;         // --frame-range MIN,MAX
  double frames_range[2] = {0, 0};
  bool frames_view_set = false;  // --frame-view X1,Y1,X2,Y2
  double frames_view[4] = {0, 0, 0, 0};
  std::string frames_movie;  // --movie FILE (in the output folder)
  int models_created = 0;
  long vtu_every = 0;  // --vtu N: every model writes ParaView files every N steps into <out>/vtu
  RunLog log;          // dda run: <out>/run.log
  std::map<std::string, ResultValue> results;  // the run's results (dda.result, the script's return table)
  // dda run --restart FILE: the checkpoint's model, held until the script's
  // model of the same number (1: its first dda.model) makes its first
  // stepping call and takes its state (ScriptModel::restore).
  std::shared_ptr<ScriptModel> restart;
  std::string restart_file;
  // --checkpoint-every N | Ts: every model writes <out>/checkpoint.ckpt
  // (checkpoint_2.ckpt for the second, ...) every N steps or T s of
  // simulated time, and when Ctrl-C stops it. 0: none.
  long checkpoint_steps = 0;
  double checkpoint_seconds = 0;
  // What os.exit does in this run: given the main state and the status the
  // script asked for, ends the run (closing the state) and returns the
  // process's exit status. Empty: the state is closed and the process exits
  // with the status asked for.
  std::function<int(lua_State*, int)> on_exit;
  // --realtime F: every run without its own `realtime` option is paced to F
  // simulated seconds per wall-clock second. 0: as fast as it goes.
  double realtime = 0;
  // --live [ADDR:]PORT: the address the live view serves (empty: none), and
  // the server once started (live_server.hpp); every model made is shown.
  std::string live_address;
  std::shared_ptr<LiveServer> live;
};

// --list-params: stops the script at `what` (its first stepping call, its
// first file written) by raising ParamsOnlyStop.
void stop_if_params_only(lua_State* L, const char* what);

// Prints "dda: warning: text" on stderr and writes it to the run log of
// `dda run` (set_run_log; warnings come from places that have no Lua state,
// e.g. a frame sequence finishing its movie while the state closes, and
// from any thread: a background run's frames).
void warn(const std::string& text);
void set_run_log(RunLog* log);

// The session of this Lua state (created with defaults on first use).
Session& session(lua_State* L);
// Replaces the session (called by `dda run` / `dda console` before loading the script).
void set_session(lua_State* L, Session s);

// ---- Ctrl-C and SIGTERM -------------------------------------------------------
// While installed, SIGINT and SIGTERM set a flag that stepping loops check
// at every step boundary (they stop, write a final checkpoint when the run
// writes them, flush and raise "interrupted"), and, like lua.c, a hook that
// stops plain Lua code too. A second signal before the first is handled
// kills the process the default way. `dda run` then exits 128 + the signal
// (130 for Ctrl-C, 143 for SIGTERM).
void install_interrupt_handler(lua_State* L);
void remove_interrupt_handler();
bool interrupt_requested();
int interrupt_signal();        // SIGINT or SIGTERM, 0 while none came
const char* interrupt_name();  // "interrupted (Ctrl-C)", "terminated (SIGTERM)"
void clear_interrupt();
// Throws Interrupted if Ctrl-C was pressed (called between steps).
void check_interrupt(const char* where_text);

// ---- Progress line ------------------------------------------------------------
// "t = 1.20e-03 s / 3.00e-03 s | step 600 | 850 steps/s | ETA 2 s" on stderr:
// on a terminal redrawn at most 5 times a second and erased when the stepping
// call ends; otherwise as plain lines "progress: t = ... (40 %) ...", one each
// Session::progress_seconds and one per 5 % done (at most one a second).
class Progress {
 public:
  Progress(lua_State* L, double t_start, double t_end, long step_start, long step_end);
  ~Progress();
  void update(double t, long step);

 private:
  ProgressMode mode_ = ProgressMode::None;
  double line_seconds_ = 10;
  bool drawn_ = false;
  double next_fraction_ = 0.05;  // Lines: the next 5 % mark
  double t_start_, t_end_;
  long step_start_, step_end_;
  std::chrono::steady_clock::time_point start_, last_;
  std::string text(double t, long step, double elapsed, double fraction) const;
};

}  // namespace dda::script
