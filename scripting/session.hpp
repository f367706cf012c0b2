#pragma once
// What a script run shares across every model it builds: the output folder,
// the --set parameters, the --threads override, whether to draw a progress
// line, and the Ctrl-C flag. One Session lives in each lua_State's registry
// (a default one is created on first use, e.g. when a test opens the module
// directly).
#include <lua.hpp>

#include <chrono>
#include <filesystem>
#include <map>
#include <set>
#include <string>

namespace dda::script {

struct Session {
  std::filesystem::path out_dir = "out";
  std::map<std::string, std::string> params;  // --set NAME=VALUE
  std::set<std::string> params_read;          // names the script asked for
  int threads = -1;                           // --threads N (−1: leave to the script)
  bool quiet = false;                         // --quiet
  bool progress = false;                      // draw the progress line (a terminal, not quiet)
  std::set<std::string> files;                // CSV files opened in this run (no two monitors share one)
  std::string script;                         // the script being run (for messages)
  // --frames N [--frame-field F] [--frame-size WxH]: every model the script
  // creates writes a frame every N steps into <out>/frames (frames_2, ... for
  // later models). 0: none.
  long frames_every = 0;
  std::string frames_field = "sigma_xx";
  int frames_width = 1280, frames_height = 720;
  int models_created = 0;
};

// The session of this Lua state (created with defaults on first use).
Session& session(lua_State* L);
// Replaces the session (called by `dda run` / `dda console` before loading the script).
void set_session(lua_State* L, Session s);

// ---- Ctrl-C -----------------------------------------------------------------
// While installed, SIGINT sets a flag that stepping loops check at every step
// boundary (they stop, flush and raise "interrupted"), and, like lua.c, a hook
// that stops plain Lua code too. A second Ctrl-C before the first is handled
// kills the process the default way.
void install_interrupt_handler(lua_State* L);
void remove_interrupt_handler();
bool interrupt_requested();
void clear_interrupt();
// Throws Interrupted if Ctrl-C was pressed (called between steps).
void check_interrupt(const char* where_text);

// ---- Progress line ------------------------------------------------------------
// "t = 1.20e-03 s / 3.00e-03 s | step 600 | 850 steps/s | ETA 2 s" on stderr,
// redrawn at most 5 times a second, only when Session::progress is set, and
// erased when the stepping call ends.
class Progress {
 public:
  Progress(lua_State* L, double t_start, double t_end, long step_start, long step_end);
  ~Progress();
  void update(double t, long step);

 private:
  bool enabled_ = false;
  bool drawn_ = false;
  double t_start_, t_end_;
  long step_start_, step_end_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace dda::script
