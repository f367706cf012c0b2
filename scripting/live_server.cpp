// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "live_server.hpp"

#include "core/error.hpp"
#include "session.hpp"

#ifdef DDA_HAVE_LIVE_VIEW

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <thread>
#include <vector>

#include "live_page.hpp"  // kLivePage: live/page.html, embedded at configure time
#include "model.hpp"
#include "run_control.hpp"

#ifdef DDA_HAVE_RENDER
#include "render.hpp"
#endif

// Last: it brings <resolv.h>, whose macro _res breaks Eigen's headers.
#include <httplib.h>

namespace dda::script {

namespace {

using Clock = std::chrono::steady_clock;

// ---- JSON, written by hand (numbers, strings, arrays) -----------------------------------

void json_string(std::string& out, const std::string& s) {
  out += '"';
  for (const unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  out += '"';
}

void json_number(std::string& out, double v) {
  if (!std::isfinite(v)) {
    out += "null";
    return;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  out += buf;
}

// "key":value pairs of an object being written.
struct JsonObject {
  std::string& out;
  bool first = true;
  explicit JsonObject(std::string& o) : out(o) { out += '{'; }
  ~JsonObject() { out += '}'; }
  std::string& key(const char* k) {
    if (!first) out += ',';
    first = false;
    json_string(out, k);
    out += ':';
    return out;
  }
  void number(const char* k, double v) { json_number(key(k), v); }
  void string(const char* k, const std::string& v) { json_string(key(k), v); }
  void boolean(const char* k, bool v) { key(k) += v ? "true" : "false"; }
};

// The HTTP threads serve a person watching: they yield the CPU to the run.
void lower_priority() {
  thread_local bool done = false;
  if (done) return;
  done = true;
  setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 10);
}

// One page's view of the monitors: the rows it has been sent so far.
struct Client {
  std::vector<std::size_t> sent;
  int model = -1;  // the model those rows were of
  Clock::time_point last_wall = Clock::now();
  long last_step = -1;
  double last_t = 0;
  double steps_per_second = 0, sim_per_second = 0;
};

}  // namespace

struct LiveServer::Impl {
  httplib::Server http;
  std::thread thread;
  std::string host, script;
  int port = 0;
  std::atomic<bool> ending{false}, stopping{false};

  std::mutex status_m;
  Client status_client;  // GET /status's rates

  std::mutex shown_m;
  std::shared_ptr<RunControl> shown;  // the model on the page
  int shown_id = 0;                   // counts the models shown

#ifdef DDA_HAVE_RENDER
  // Frames: one at a time, from the model shown.
  std::mutex frame_m;
  render::Renderer renderer;
  render::WorldSnapshot snapshot;  // the shown model's start and monitors
  int snapshot_model = -1, snapshot_monitors = 0;
  Clock::time_point next_render = Clock::now();
  long renders = 0;
  std::string cached_key;
  std::string cached_png;
#endif

  std::pair<std::shared_ptr<RunControl>, int> current() {
    std::lock_guard g(shown_m);
    return {shown, shown_id};
  }

  // `client`: the page's rates and the monitor rows it has had (none
  // with `monitors` false); `first`: its first status.
  std::string status(Client& client, bool first, bool monitors = true);
  void fill_status(JsonObject& o, Client& client, bool first, bool monitors);
  bool frame(const httplib::Request& req, httplib::Response& res);
  void control(bool pause, httplib::Response& res);
};

// The status the page shows, and the monitors' rows it has not had yet.
std::string LiveServer::Impl::status(Client& client, bool first, bool monitors) {
  std::string out;
  {
    JsonObject o(out);
    fill_status(o, client, first, monitors);
  }
  return out;
}

void LiveServer::Impl::fill_status(JsonObject& o, Client& client, bool first, bool monitors) {
  const auto [control, model_id] = current();
  o.string("script", script);
  o.boolean("ending", ending.load());
  o.number("model", model_id);
  if (!control) {
    o.string("state", "no model yet");
    return;
  }
  const RunState state = control->state();
  const RunPlanView plan = control->plan();
  const bool active = state == RunState::Running || state == RunState::Paused;
  std::lock_guard hold(control->lock);  // between two steps
  ScriptModel* m = control->model();
  if (!m || m->closed()) {
    o.string("state", "closed");
    return;
  }
  o.string("state", control->holding_next() ? "paused" : to_string(state));  // (the next run begins paused)
  o.boolean("background", plan.background);
  const World& w = m->world();
  const double t = w.time();
  const long step = w.step_count();
  // Steps per second and simulated seconds per second, over the last half second or more.
  const auto now = Clock::now();
  const double span = std::chrono::duration<double>(now - client.last_wall).count();
  if (client.last_step < 0 || step < client.last_step || client.model != model_id) {
    client.last_step = step, client.last_t = t, client.last_wall = now;
    client.steps_per_second = client.sim_per_second = 0;
  } else if (span >= 0.5) {
    client.steps_per_second = (step - client.last_step) / span;
    client.sim_per_second = (t - client.last_t) / span;
    client.last_step = step, client.last_t = t, client.last_wall = now;
  }
  o.number("t", t);
  o.number("step", static_cast<double>(step));
  o.number("dt", w.current_dt());
  o.number("blocks", static_cast<double>(w.block_count()));
  o.number("contacts", static_cast<double>(w.contacts().size()));
  o.number("steps_per_second", active && state == RunState::Running ? client.steps_per_second : 0);
  o.number("sim_per_second", active && state == RunState::Running ? client.sim_per_second : 0);
  if (active) {
    o.number("t_start", plan.t_start);
    o.number("t_end", plan.t_end);
    o.number("step_start", static_cast<double>(plan.step_start));
    o.number("step_end", static_cast<double>(plan.step_end));
    o.number("realtime", plan.realtime);
    o.number("behind", control->behind());
    double fraction = -1, eta = -1;
    if (plan.t_end > plan.t_start) {
      fraction = (t - plan.t_start) / (plan.t_end - plan.t_start);
      if (client.sim_per_second > 0) eta = (plan.t_end - t) / client.sim_per_second;
    } else if (plan.step_end > plan.step_start) {
      fraction = static_cast<double>(step - plan.step_start) / static_cast<double>(plan.step_end - plan.step_start);
      if (client.steps_per_second > 0) eta = (plan.step_end - step) / client.steps_per_second;
    }
    o.number("fraction", fraction);
    o.number("eta", eta);
  }
  const StepStats& st = w.last_stats();
  {
    std::string& p = o.key("profile");
    JsonObject stages(p);
    for (int k = 0; k < kStageCount; ++k) stages.number(kStageKeys[k], st.profile.seconds[k]);
    stages.number("total", st.profile.total);
  }
  {
    std::string& p = o.key("iterations");
    JsonObject it(p);
    it.number("open_close", st.open_close_iterations);
    it.number("cg", st.cg_iterations);
    it.number("patch", st.patch_iterations);
    it.number("step_cuts", st.step_cuts);
    it.string("solver", st.solver ? st.solver : "");
  }
  // The monitors: rows since the last message, every k-th (the last always)
  // so that a message carries at most `limit` rows of each.
  const bool reset = first || client.model != model_id;
  client.model = model_id;
  if (!monitors) return;
  if (reset) client.sent.assign(static_cast<std::size_t>(m->monitor_count()), 0);
  client.sent.resize(static_cast<std::size_t>(m->monitor_count()), 0);
  o.boolean("reset", reset);
  std::string& mons = o.key("monitors");
  mons += '[';
  for (int i = 0; i < m->monitor_count(); ++i) {
    const Monitor& mon = m->monitor(i);
    std::size_t& sent = client.sent[static_cast<std::size_t>(i)];
    if (sent > mon.times.size()) sent = 0;  // fewer rows than before: a restart
    const std::size_t n = mon.times.size(), limit = reset ? 2000 : 400;
    const std::size_t stride = std::max<std::size_t>(1, (n - sent + limit - 1) / limit);
    if (i) mons += ',';
    JsonObject mo(mons);
    mo.string("name", mon.name);
    std::string& fields = mo.key("fields");
    fields += '[';
    for (std::size_t k = 0; k < mon.fields.size(); ++k) {
      if (k) fields += ',';
      json_string(fields, field_name(mon.fields[k]));
    }
    fields += ']';
    std::vector<std::size_t> rows;
    for (std::size_t r = sent + stride - 1; r < n; r += stride) rows.push_back(r);
    if (n > sent && (rows.empty() || rows.back() != n - 1)) rows.push_back(n - 1);
    std::string& ts = mo.key("t");
    ts += '[';
    for (std::size_t j = 0; j < rows.size(); ++j) {
      if (j) ts += ',';
      json_number(ts, mon.times[rows[j]]);
    }
    ts += ']';
    std::string& vs = mo.key("v");
    vs += '[';
    for (std::size_t k = 0; k < mon.fields.size(); ++k) {
      if (k) vs += ',';
      vs += '[';
      for (std::size_t j = 0; j < rows.size(); ++j) {
        if (j) vs += ',';
        json_number(vs, k < mon.values.size() && rows[j] < mon.values[k].size() ? mon.values[k][rows[j]] : NAN);
      }
      vs += ']';
    }
    vs += ']';
    sent = n;
  }
  mons += ']';
}

#ifdef DDA_HAVE_RENDER
// GET /frame.png: a snapshot copied between two steps, rendered here, no
// faster than keeps rendering under kRenderShare of the wall clock; the same
// picture again while the model has not moved.
bool LiveServer::Impl::frame(const httplib::Request& req, httplib::Response& res) {
  render::FrameOptions o;
  o.width = 960, o.height = 540;
  try {
    if (req.has_param("field")) o.field = render::parse_field(req.get_param_value("field"));
    if (req.has_param("w")) o.width = std::clamp(std::atoi(req.get_param_value("w").c_str()), 64, 2048);
    if (req.has_param("h")) o.height = std::clamp(std::atoi(req.get_param_value("h").c_str()), 64, 2048);
    if (req.has_param("range")) {
      double lo = 0, hi = 0;
      if (std::sscanf(req.get_param_value("range").c_str(), "%lf,%lf", &lo, &hi) != 2 || !(hi > lo))
        throw Error("range must be MIN,MAX with MIN < MAX");
      o.range = render::ValueRange{lo, hi};
    }
    o.show_joint_state = req.has_param("joints") && req.get_param_value("joints") == "1";
    o.validate();
  } catch (const std::exception& e) {
    res.status = 400;
    res.set_content(e.what(), "text/plain");
    return true;
  }
  std::lock_guard frames(frame_m);
  const auto [control, model_id] = current();
  if (!control) {
    res.status = 404;
    res.set_content("no model yet", "text/plain");
    return true;
  }
  while (Clock::now() < next_render && !stopping && !ending) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  render::Scene scene;
  auto start = Clock::now();
  {
    std::lock_guard hold(control->lock);  // between two steps
    start = Clock::now();                 // (the wait for the step in progress costs the run nothing)
    ScriptModel* m = control->model();
    if (!m || m->closed() || m->world().block_count() == 0) {
      res.status = 404;
      res.set_content("the model has no blocks", "text/plain");
      return true;
    }
    if (snapshot_model != model_id) {
      snapshot = render::WorldSnapshot();
      snapshot_model = model_id;
      snapshot_monitors = 0;
    }
    for (; snapshot_monitors < m->monitor_count(); ++snapshot_monitors)
      snapshot.add_monitor(m->monitor(snapshot_monitors).tracked, m->monitor(snapshot_monitors).name);
    scene = snapshot.take(m->world(), o.show_joint_state);
  }
  const std::string key = msg(model_id, ":", scene.step, ":", req.get_param_value("field"), ":", o.width, "x", o.height,
                              ":", req.get_param_value("range"), ":", o.show_joint_state);
  if (key != cached_key) {
    const render::Frame f = renderer.render(scene, o);
    const std::vector<std::uint8_t> png = render::encode_png(f.image);
    cached_png.assign(png.begin(), png.end());
    cached_key = key;
    // The next frame waits so that rendering keeps to its share of the
    // wall clock (the first, which creates the OpenGL context, sets no pace).
    const double took = std::chrono::duration<double>(Clock::now() - start).count();
    if (renders++ > 0)
      next_render = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                       std::chrono::duration<double>(took * (1 / kRenderShare - 1)));
  }
  const render::Box b = scene.bounds();
  res.set_header("X-DDA-Aspect", msg(b.height() > 0 ? b.width() / b.height() : 1.0));
  res.set_header("Cache-Control", "no-store");
  res.set_header("X-DDA-Step", std::to_string(scene.step));
  res.set_header("X-DDA-Time", msg(scene.time));
  res.set_content(cached_png, "image/png");
  return true;
}
#else
bool LiveServer::Impl::frame(const httplib::Request&, httplib::Response& res) {
  res.status = 404;
  res.set_content("this dda was built without the renderer", "text/plain");
  return true;
}
#endif

void LiveServer::Impl::control(bool pause, httplib::Response& res) {
  const auto [c, id] = current();
  const bool changed = c && (pause ? c->hold_next() : c->resume());
  std::string out;
  {
    JsonObject o(out);
    o.boolean("ok", changed);
    o.string("state", !c ? "no model yet" : c->holding_next() ? "paused" : to_string(c->state()));
  }
  res.set_header("Cache-Control", "no-store");
  res.set_content(out, "application/json");
}

LiveServer::LiveServer(const std::string& address, const std::string& script) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.script = script;
  const auto colon = address.rfind(':');
  s.host = colon == std::string::npos ? "127.0.0.1" : address.substr(0, colon);
  const std::string port = colon == std::string::npos ? address : address.substr(colon + 1);
  char* end = nullptr;
  const long p = std::strtol(port.c_str(), &end, 10);
  if (port.empty() || *end != '\0' || p < 0 || p > 65535 || s.host.empty())
    throw Error(
        msg("--live needs [ADDR:]PORT (e.g. 8080 or 0.0.0.0:8080; PORT 0: any free port), got '", address, "'"));

  s.http.new_task_queue = [] { return new httplib::ThreadPool(6); };
  // SO_REUSEADDR only: cpp-httplib's default SO_REUSEPORT would let a second
  // dda bind the same port and share its connections.
  s.http.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  s.http.Get("/", [&s](const httplib::Request&, httplib::Response& res) {
    lower_priority();
    res.set_header("Cache-Control", "no-store");
    res.set_content(kLivePage, "text/html; charset=utf-8");
  });
  s.http.Get("/status", [&s](const httplib::Request&, httplib::Response& res) {
    lower_priority();
    std::string text;
    {
      std::lock_guard g(s.status_m);  // one rate for every /status caller
      text = s.status(s.status_client, false, false);
    }
    res.set_header("Cache-Control", "no-store");
    res.set_content(text, "application/json");
  });
  s.http.Get("/events", [&s](const httplib::Request& req, httplib::Response& res) {
    lower_priority();
    double every = 0.25;
    if (req.has_param("every")) every = std::clamp(std::atof(req.get_param_value("every").c_str()), 0.1, 5.0);
    auto client = std::make_shared<Client>();
    auto first = std::make_shared<bool>(true);
    res.set_header("Cache-Control", "no-store");
    res.set_chunked_content_provider(
        "text/event-stream", [&s, client, first, every](std::size_t, httplib::DataSink& sink) {
          if (!*first) {
            const auto until =
                Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(every));
            while (Clock::now() < until && !s.stopping && !s.ending)
              std::this_thread::sleep_for(std::chrono::milliseconds(20));
          }
          if (s.stopping || !sink.is_writable()) return false;
          const bool ending = s.ending;
          const std::string message = "event: status\ndata: " + s.status(*client, *first) + "\n\n";
          *first = false;
          if (!sink.write(message.data(), message.size())) return false;
          if (ending) {
            sink.done();
            return true;
          }
          return true;
        });
  });
  s.http.Get("/frame.png", [&s](const httplib::Request& req, httplib::Response& res) {
    lower_priority();
    s.frame(req, res);
  });
  s.http.Post("/pause", [&s](const httplib::Request&, httplib::Response& res) { s.control(true, res); });
  s.http.Post("/resume", [&s](const httplib::Request&, httplib::Response& res) { s.control(false, res); });

  if (p == 0) {
    s.port = s.http.bind_to_any_port(s.host);
    if (s.port <= 0) throw Error(msg("cannot serve the live view on ", s.host, ": no port could be bound there"));
  } else {
    if (!s.http.bind_to_port(s.host, static_cast<int>(p)))
      throw Error(msg("cannot serve the live view on ", s.host, ":", p,
                      ": the port is in use or the address is not this machine's (give another: --live PORT)"));
    s.port = static_cast<int>(p);
  }
  s.thread = std::thread([&s] { s.http.listen_after_bind(); });
}

LiveServer::~LiveServer() {
  Impl& s = *impl_;
  // The pages get one last status saying the run ended, then the server stops.
  s.ending = true;
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  s.stopping = true;
  s.http.stop();
  if (s.thread.joinable()) s.thread.join();
}

std::string LiveServer::url() const { return msg("http://", impl_->host, ":", impl_->port, "/"); }

void LiveServer::show(ScriptModel& model) {
  std::lock_guard g(impl_->shown_m);
  impl_->shown = model.shared_control();
  ++impl_->shown_id;
}

bool start_live_view(lua_State* L, const std::string& script, std::string& error) {
  Session& s = session(L);
  if (s.live_address.empty()) return true;
  try {
    s.live = std::make_shared<LiveServer>(s.live_address, script);
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
  std::fprintf(stderr, "dda: live view at %s\n", s.live->url().c_str());
  std::fflush(stderr);
  s.log.line("live view at " + s.live->url());
  return true;
}

void show_live(lua_State* L, ScriptModel& model) {
  if (const auto& live = session(L).live) live->show(model);
}

}  // namespace dda::script

#else  // built without cpp-httplib

namespace dda::script {

bool start_live_view(lua_State* L, const std::string&, std::string& error) {
  if (session(L).live_address.empty()) return true;
  error =
      "--live: this dda was built without the live view (cpp-httplib not found: apt-get install libcpp-httplib-dev)";
  return false;
}

void show_live(lua_State*, ScriptModel&) {}

}  // namespace dda::script

#endif
