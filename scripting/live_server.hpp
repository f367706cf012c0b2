// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The live view: `dda run SCRIPT --live [ADDR:]PORT` and `dda console --live
// [ADDR:]PORT` serve a page (plain HTML and JavaScript, embedded in the
// binary: no network, no build step) at http://ADDR:PORT/ (ADDR defaults to
// 127.0.0.1, this machine only) that shows the run as it goes: the latest
// frame in the field chosen on the page, the monitors' histories as plots,
// t, step, steps/s, ETA, the step's profile and iteration counts, and pause
// and resume buttons that act as m:pause() and m:resume() do.
//
// HTTP is Debian's cpp-httplib: one small packaged library, whose chunked
// content providers carry Server-Sent Events. The page's status and plots
// come pushed as events (GET /events); frames it fetches when it is ready
// for the next (GET /frame.png), rendered on the server's own threads from a
// snapshot copied between two steps (run_control.hpp), no faster than keeps
// their share of the wall clock under kRenderShare.
//
//   GET  /             the page
//   GET  /events       Server-Sent Events: "status" (JSON) every 0.25 s (?every=S, 0.1 .. 5)
//   GET  /status       one status (JSON)
//   GET  /frame.png    ?field=sigma_xx&w=960&h=540[&range=MIN,MAX][&joints=1]
//   POST /pause        the run shown pauses between two steps
//   POST /resume       and goes on
#include <lua.hpp>

#include <memory>
#include <string>

namespace dda::script {

class ScriptModel;

// Rendering for the live view takes at most this share of wall-clock time.
inline constexpr double kRenderShare = 0.03;

class LiveServer {
 public:
  // Serves at "[ADDR:]PORT" (PORT 0: any free port). Throws dda::Error
  // naming the address when it cannot.
  LiveServer(const std::string& address, const std::string& script);
  ~LiveServer();  // tells the page the run ended, stops serving
  LiveServer(const LiveServer&) = delete;
  LiveServer& operator=(const LiveServer&) = delete;

  std::string url() const;  // "http://127.0.0.1:8080/"
  // The model the page shows from now on (the latest one a script made).
  void show(ScriptModel& model);

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// Starts the live view the session asks for (--live), printing its address;
// false and `error` when it cannot serve there. `script` titles the page.
bool start_live_view(lua_State* L, const std::string& script, std::string& error);

// A new model: the live view, if any, shows it.
void show_live(lua_State* L, ScriptModel& model);

}  // namespace dda::script
