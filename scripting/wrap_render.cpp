// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Rendering from Lua (render/), when the renderer is built:
//   m:frame{file = "t.png", field = "sigma_xx", ...}     one frame now
//   m:frames{folder = "frames", every = 10, ...}         a numbered sequence during the run (dda.Frames)
//   dda.plot{file = "p.png", series = {...}, ...}        a line plot of histories
//   monitor:plot{field = "sxx", file = "p.png", ...}     a monitor's history
// Frames are captured on the Lua thread between steps (a copy of the World's
// arrays) and rendered and encoded on the renderer's worker thread.
#include "wrap.hpp"

#ifdef DDA_HAVE_RENDER

#include <cmath>
#include <cstring>

#include "render.hpp"
#include "session.hpp"

namespace dda::script {

namespace {

constexpr const char* kFramesType = "dda.Frames";

// The model's rendering state: where blocks started (for magnified
// deformation), the monitors to mark, and the frame sequences.
struct RenderHook : StepHook {
  render::WorldSnapshot snapshot;  // for single frames
  std::vector<std::unique_ptr<render::FrameSequence>> sequences;

  void before_step(const World& w) override {
    if (!snapshot.has_initial()) snapshot.record_initial(w);
    for (auto& s : sequences) {
      if (!s->snapshot().has_initial()) s->snapshot().record_initial(w);
      s->maybe_capture(w);  // the state before the first step (a no-op when already taken)
    }
  }
  void after_step(const World& w) override {
    for (auto& s : sequences) s->maybe_capture(w);
  }
  void monitor_added(int tracked, const std::string& name) override {
    snapshot.add_monitor(tracked, name);
    for (auto& s : sequences) s->snapshot().add_monitor(tracked, name);
  }
};

RenderHook& render_hook(ScriptModel& m) {
  for (const auto& h : m.hooks())
    if (auto* r = dynamic_cast<RenderHook*>(h.get())) return *r;
  auto hook = std::make_unique<RenderHook>();
  for (int i = 0; i < m.monitor_count(); ++i) hook->snapshot.add_monitor(m.monitor(i).tracked, m.monitor(i).name);
  return static_cast<RenderHook&>(m.add_hook(std::move(hook)));
}

std::filesystem::path in_out_dir(lua_State* L, const std::string& file) {
  const std::filesystem::path p(file);
  return p.is_absolute() ? p : session(L).out_dir / p;
}

void create_parent(const std::filesystem::path& p, const std::string& call) {
  if (!p.has_parent_path()) return;
  std::error_code ec;
  std::filesystem::create_directories(p.parent_path(), ec);
  if (ec) fail(call, ": cannot create the folder '", p.parent_path().string(), "': ", ec.message());
}

render::Rgb read_rgb(const Options& o, const char* key) {
  lua_State* L = o.state();
  o.push(key);
  const int t = lua_gettop(L);
  if (lua_type(L, t) != LUA_TTABLE || lua_rawlen(L, t) != 3)
    fail(o.call(), ": option '", key, "' must be {r, g, b} (0-255)");
  int c[3];
  for (int k = 0; k < 3; ++k) {
    lua_rawgeti(L, t, k + 1);
    const double v = lua_tonumber(L, -1);
    const bool ok = lua_type(L, -1) == LUA_TNUMBER && v >= 0 && v <= 255;
    lua_pop(L, 1);
    if (!ok) fail(o.call(), ": option '", key, "' must be {r, g, b} with each in 0-255");
    c[k] = static_cast<int>(v + 0.5);
  }
  lua_pop(L, 1);
  return render::Rgb{static_cast<std::uint8_t>(c[0]), static_cast<std::uint8_t>(c[1]), static_cast<std::uint8_t>(c[2])};
}

// What a frame shows (render::FrameOptions), for m:frame and m:frames.
constexpr Name kFrameOptions[] = {
    {"field",
     "what colours the blocks: `\"sigma_xx\"`, `\"sigma_yy\"`, `\"tau_xy\"`, `\"sigma_1\"`, `\"von_mises\"` (MPa), "
     "`\"velocity\"` (m/s), `\"displacement\"` (m) or `\"none\"`",
     "\"sigma_yy\""},
    {"width", "pixels, 16 to 8192", "1280"},
    {"height", "pixels, 16 to 8192", "720"},
    {"colormap", "`\"coolwarm\"` (blue compression, red tension) or `\"viridis\"`",
     "coolwarm for signed fields, viridis for magnitudes"},
    {"range",
     "{min, max}: a fixed colour range in SI units (Pa, m/s, m); `\"frame\"`: each frame's own, ±max|value| or "
     "[0, max]; in m:frames also `\"grow\"`: the widest so far",
     "\"frame\""},
    {"view", "{x1, y1, x2, y2}: the world window shown (m)", "the model's bounds plus 4 %"},
    {"magnify", "deformation drawn magnified: initial + magnify × (current − initial)", "1"},
    {"edges", "draw the block outlines (joints)", "true"},
    {"edge_width", "their width (pixels)", "1"},
    {"contacts", "mark contact vertices: open white, sliding magenta, locked black", "false"},
    {"monitors", "mark monitor points with their names", "true"},
    {"velocity", "velocity arrows at block centroids, with a reference arrow", "false"},
    {"arrow_scale", "arrow length (m) per m/s", "the longest arrow 6 % of the view"},
    {"colorbar", "a colour bar with ticks, the field's name and unit", "true"},
    {"info", "a top line: title or field, time and step", "true"},
    {"title", "replaces the field's name on the top line", "the field's name"},
    {"background", "{r, g, b} (0-255)", "{255, 255, 255}"},
    {"supersample", "1 to 4: drawn at k× size and averaged (smoother edges)", "1"},
    {"scale", "a scale bar (and the magnification when magnify ≠ 1)", "true"},
    {"joints", "failed joints drawn in red over the edges", "false"}};

// `grow` (sequences only): set when range = "grow" asks for a range that
// widens with the data; nullptr refuses it (a single frame).
render::FrameOptions read_frame_options(const Options& o, bool* grow = nullptr) {
  render::FrameOptions f;
  if (o.has("field")) f.field = render::parse_field(o.string("field"));
  f.width = static_cast<int>(o.integer("width", f.width));
  f.height = static_cast<int>(o.integer("height", f.height));
  if (o.has("colormap")) f.colormap = render::parse_colormap(o.string("colormap"));
  const bool range_named = o.push("range") == LUA_TSTRING;
  lua_pop(o.state(), 1);
  if (range_named) {
    const std::string r = o.string("range");
    if (r == "grow" && grow)
      *grow = true;
    else if (r != "frame")
      fail(o.call(), ": option 'range' must be {min, max}", grow ? ", \"frame\" or \"grow\"" : " or \"frame\"",
           ", got \"", r, "\"");
  } else if (o.has("range")) {
    const Vec2 r = o.point("range");
    if (!(r.y() > r.x())) fail(o.call(), ": option 'range' must be {min, max} with min < max");
    f.range = render::ValueRange{r.x(), r.y()};
  }
  if (o.has("view")) {
    const auto q = o.quad("view");
    f.view = render::Box{std::min(q[0], q[2]), std::min(q[1], q[3]), std::max(q[0], q[2]), std::max(q[1], q[3])};
  }
  f.magnify = o.positive("magnify", f.magnify);
  f.show_edges = o.boolean("edges", f.show_edges);
  f.edge_width = o.positive("edge_width", f.edge_width);
  f.show_contacts = o.boolean("contacts", f.show_contacts);
  f.show_monitors = o.boolean("monitors", f.show_monitors);
  f.show_velocity = o.boolean("velocity", f.show_velocity);
  f.arrow_scale = o.non_negative("arrow_scale", f.arrow_scale);
  f.show_colorbar = o.boolean("colorbar", f.show_colorbar);
  f.show_scale = o.boolean("scale", f.show_scale);
  f.show_joint_state = o.boolean("joints", f.show_joint_state);
  f.show_info = o.boolean("info", f.show_info);
  f.title = o.string("title", f.title);
  if (o.has("background")) f.background = read_rgb(o, "background");
  f.supersample = static_cast<int>(o.integer("supersample", f.supersample));
  f.validate();
  return f;
}

// Options made of `first` and then `rest`.
std::vector<Name> joined(std::initializer_list<Name> first, Names rest) {
  std::vector<Name> n(first);
  n.insert(n.end(), rest.begin(), rest.end());
  return n;
}

const std::vector<Name> kFrameCallOptions =
    joined({{"file", "the PNG file (a relative name goes into the output folder)", nullptr}}, kFrameOptions);
const std::vector<Name> kFramesOptions = joined(
    {{"folder", "its folder (a relative name goes into the output folder)", "\"frames\""},
     {"every", "a frame every this many steps", "—"},
     {"every_time", "a frame each time the simulated time passes a multiple of this (s)", "—"},
     {"steps", "{first, last}: frames only in these steps (last -1: no end)", "every step"},
     {"times", "{t0, t1}: frames only in these times (s; t1 -1: no end)", "every time"},
     {"movie", "a movie made from the frames when the sequence ends, if ffmpeg is on the PATH (e.g. \"film.mp4\")",
      "none"},
     {"fps", "the movie's frames per second", "30"},
     {"fixed", "view and arrow scale fixed from the first frame (false: each frame its own)", "true"},
     {"prefix", "file name stem", "the field's name"},
     {"digits", "zero-padded width of the frame number", "5"},
     {"on_error", "`\"stop\"` the run when a frame cannot be written, or `\"continue\"` with a warning", "\"stop\""}},
    kFrameOptions);

// m:frame{file = "frame.png", field = ..., ...} → path written
int m_frame(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:frame");
  check_not_busy(m, "m:frame");
  const Options o(L, 2, "m:frame", kFrameCallOptions);
  const render::FrameOptions f = read_frame_options(o);
  const auto path = in_out_dir(L, o.string("file"));
  create_parent(path, "m:frame");
  RenderHook& hook = render_hook(m);
  render::write_frame(m.world(), path, f, hook.snapshot.has_initial() ? &hook.snapshot : nullptr);
  lua_pushstring(L, path.c_str());
  return 1;
}

// m:frames{folder = "frames", every = N | every_time = dt, prefix, digits, on_error = "stop" | "continue", ...}
int m_frames(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:frames");
  check_not_busy(m, "m:frames");
  const Options o(L, 2, "m:frames", kFramesOptions);
  render::SequenceOptions so;
  so.frame = read_frame_options(o, &so.grow_range);
  so.folder = in_out_dir(L, o.string("folder", "frames"));
  so.prefix = o.string("prefix", "");
  so.every_steps = o.integer("every", 0);  // 0: not given (every_time, or every step)
  if (o.has("every") && so.every_steps < 1)
    fail("m:frames: option 'every' must be a whole number of steps >= 1, got ", so.every_steps);
  so.every_time = o.non_negative("every_time", 0);
  so.digits = static_cast<int>(o.integer("digits", so.digits));
  so.fixed = o.boolean("fixed", so.fixed);
  if (o.has("steps")) {
    const Vec2 w = o.point("steps");
    if (w.x() != std::floor(w.x()) || w.y() != std::floor(w.y()) || w.x() < 0)
      fail("m:frames: option 'steps' must be {first, last} whole step numbers >= 0 (last -1: no end)");
    so.from_step = static_cast<long>(w.x());
    so.to_step = static_cast<long>(w.y());
  }
  if (o.has("times")) {
    const Vec2 w = o.point("times");
    so.from_time = w.x();
    so.to_time = w.y();
  }
  if (o.has("movie")) so.movie = in_out_dir(L, o.string("movie"));
  so.fps = static_cast<int>(o.integer("fps", so.fps));
  const std::string on_error = o.string("on_error", "stop");
  if (on_error == "stop")
    so.on_error = render::OnError::Stop;
  else if (on_error == "continue")
    so.on_error = render::OnError::Continue;
  else
    fail("m:frames: option 'on_error' must be \"stop\" or \"continue\", got \"", on_error, "\"");
  so.warn = [](const std::string& text) { warn(text); };
  RenderHook& hook = render_hook(m);
  auto seq = std::make_unique<render::FrameSequence>(std::move(so));
  for (int i = 0; i < m.monitor_count(); ++i) seq->snapshot().add_monitor(m.monitor(i).tracked, m.monitor(i).name);
  if (m.world().step_count() == 0 && m.world().block_count() > 0) seq->snapshot().record_initial(m.world());
  hook.sequences.push_back(std::move(seq));
  push_handle(L, 1, kFramesType, static_cast<int>(hook.sequences.size()) - 1);
  return 1;
}

render::FrameSequence& self_frames(lua_State* L, const char* call) {
  Handle* h = check_handle(L, 1, kFramesType, call, "self");
  RenderHook& hook = render_hook(*h->model);
  if (h->id < 0 || h->id >= static_cast<int>(hook.sequences.size()))
    fail(call, ": attempt to use an invalid frame sequence");
  return *hook.sequences[h->id];
}

int fr_count(lua_State* L) {
  lua_pushinteger(L, self_frames(L, "frames:count").frame_count());
  return 1;
}
// frames:capture(): a frame now, due or not
int fr_capture(lua_State* L) {
  Handle* h = check_handle(L, 1, kFramesType, "frames:capture", "self");
  self_frames(L, "frames:capture").capture(h->model->world());
  return 0;
}
// frames:flush(): waits for the queued frames; raises their errors
int fr_flush(lua_State* L) {
  self_frames(L, "frames:flush").flush();
  return 0;
}
// frames:finish() → the movie's path, or nil
int fr_finish(lua_State* L) {
  const auto movie = self_frames(L, "frames:finish").finish();
  if (movie.empty())
    lua_pushnil(L);
  else
    lua_pushstring(L, movie.c_str());
  return 1;
}
int fr_path(lua_State* L) {
  render::FrameSequence& s = self_frames(L, "frames:path");
  const long i = lua_isnoneornil(L, 2) ? s.frame_count() - 1 : check_integer(L, 2, "frames:path", "argument 1 (index)");
  lua_pushstring(L, s.frame_path(static_cast<int>(i)).c_str());
  return 1;
}
int fr_folder(lua_State* L) {
  lua_pushstring(L, self_frames(L, "frames:folder").options().folder.c_str());
  return 1;
}
int fr_active(lua_State* L) {
  render::FrameSequence& s = self_frames(L, "frames:active");
  lua_pushboolean(L, s.active());
  if (s.last_error().empty()) return 1;
  lua_pushstring(L, s.last_error().c_str());
  return 2;
}
int fr_tostring(lua_State* L) {
  auto* h = static_cast<Handle*>(luaL_checkudata(L, 1, kFramesType));
  lua_pushfstring(L, "dda.Frames %d", static_cast<int>(h->id + 1));
  return 1;
}

// ---- plots ----------------------------------------------------------------------------

render::LegendPosition parse_legend(const std::string& s, const std::string& call) {
  if (s == "best") return render::LegendPosition::Best;
  if (s == "top_right") return render::LegendPosition::TopRight;
  if (s == "top_left") return render::LegendPosition::TopLeft;
  if (s == "bottom_right") return render::LegendPosition::BottomRight;
  if (s == "bottom_left") return render::LegendPosition::BottomLeft;
  if (s == "none") return render::LegendPosition::None;
  fail(call, ": option 'legend' must be best, top_right, top_left, bottom_right, bottom_left or none, got \"", s, "\"");
}

std::vector<double> read_numbers(lua_State* L, int idx, const std::string& call, const std::string& what) {
  if (lua_type(L, idx) != LUA_TTABLE) fail(call, ": ", what, " must be a list of numbers, got ", type_of(L, idx));
  const auto n = lua_rawlen(L, idx);
  std::vector<double> v(n);
  for (lua_Unsigned i = 1; i <= n; ++i) {
    lua_rawgeti(L, idx, static_cast<lua_Integer>(i));
    if (lua_type(L, -1) != LUA_TNUMBER) fail(call, ": ", what, " entry ", i, " must be a number, got ", type_of(L, -1));
    v[i - 1] = lua_tonumber(L, -1);
    lua_pop(L, 1);
  }
  return v;
}

// One series of dda.plot: {name = , x = {...}, y = {...}, color = {r, g, b},
// width = } or {name = , monitor = mon, field = "sxx"} (x = the monitor's
// times). dda.plot's documentation lists these.
constexpr Name kSeriesOptions[] = {{"name", "", ""},  {"x", "", ""},     {"y", "", ""},    {"monitor", "", ""},
                                   {"field", "", ""}, {"color", "", ""}, {"width", "", ""}};
render::Series read_series(lua_State* L, int idx, const std::string& call) {
  const Options o(L, idx, call, kSeriesOptions);
  render::Series s;
  s.name = o.string("name", "");
  if (o.has("monitor")) {
    if (o.has("x") || o.has("y")) fail(call, ": give either monitor and field, or x and y");
    o.push("monitor");
    Handle* h = check_handle(L, -1, kMonitorType, call, "option 'monitor'");
    lua_pop(L, 1);
    const Monitor& mon = h->model->monitor(h->id);
    const std::string field = o.string("field");
    const auto f = parse_field(field);
    if (!f) fail(call, ": unknown field '", field, "'; known fields: ", field_list());
    std::size_t k = mon.fields.size();
    for (std::size_t i = 0; i < mon.fields.size(); ++i)
      if (mon.fields[i] == *f) k = i;
    if (k == mon.fields.size()) fail(call, ": monitor '", mon.name, "' does not record '", field, "'");
    s.x = mon.times;
    s.y = mon.values[k];
    if (s.name.empty()) s.name = msg(mon.name, " ", field);
  } else {
    o.push("x");
    s.x = read_numbers(L, -1, call, "option 'x'");
    lua_pop(L, 1);
    o.push("y");
    s.y = read_numbers(L, -1, call, "option 'y'");
    lua_pop(L, 1);
    if (s.x.size() != s.y.size())
      fail(call, ": options 'x' and 'y' have ", s.x.size(), " and ", s.y.size(), " entries");
  }
  if (o.has("color")) s.color = read_rgb(o, "color");
  s.width = o.positive("width", s.width);
  return s;
}

// What a plot shows (render::PlotSpec), for dda.plot and monitor:plot.
constexpr Name kPlotOptions[] = {
    {"file", "the PNG file (a relative name goes into the output folder)", nullptr},
    {"title", "the plot's title", "none (monitor:plot: the monitor's name)"},
    {"x_label", "the x axis title", "\"time\""},
    {"x_unit", "its unit, shown as \"label (unit)\"", "\"s\""},
    {"y_label", "the y axis title", "none (monitor:plot: the field)"},
    {"y_unit", "its unit", "none (monitor:plot: MPa, m/s or m)"},
    {"x_scale", "data × x_scale = the axis value", "1"},
    {"y_scale", "data × y_scale = the axis value (e.g. 1e-6 for Pa → MPa)", "1 (monitor:plot of a stress: 1e-6)"},
    {"width", "pixels, 64 to 8192", "1000"},
    {"height", "pixels, 64 to 8192", "600"},
    {"x_range", "{min, max} of the x axis", "the data's, rounded out to ticks"},
    {"y_range", "{min, max} of the y axis", "the data's, rounded out to ticks"},
    {"legend", "`\"best\"`, `\"top_right\"`, `\"top_left\"`, `\"bottom_right\"`, `\"bottom_left\"` or `\"none\"`",
     "\"best\" (monitor:plot: none)"},
    {"grid", "grid lines", "true"},
    {"background", "{r, g, b} (0-255)", "{255, 255, 255}"}};

void read_plot_options(const Options& o, render::PlotSpec& p) {
  p.title = o.string("title", p.title);
  p.x_label = o.string("x_label", p.x_label);
  p.x_unit = o.string("x_unit", p.x_unit);
  p.y_label = o.string("y_label", p.y_label);
  p.y_unit = o.string("y_unit", p.y_unit);
  p.x_scale = o.number("x_scale", p.x_scale);
  p.y_scale = o.number("y_scale", p.y_scale);
  p.width = static_cast<int>(o.integer("width", p.width));
  p.height = static_cast<int>(o.integer("height", p.height));
  if (o.has("x_range")) {
    const Vec2 r = o.point("x_range");
    p.x_range = render::AxisRange{r.x(), r.y()};
  }
  if (o.has("y_range")) {
    const Vec2 r = o.point("y_range");
    p.y_range = render::AxisRange{r.x(), r.y()};
  }
  if (o.has("legend")) p.legend = parse_legend(o.string("legend"), o.call());
  p.grid = o.boolean("grid", p.grid);
  if (o.has("background")) p.background = read_rgb(o, "background");
}

const std::vector<Name> kDdaPlotOptions = joined(
    {{"series",
      "the lines: a list of {name = , x = {...}, y = {...}, color = {r, g, b}, width = (pixels, 2)}, or of {name = , "
      "monitor = m, field = \"sxx\"} (x: the monitor's times)",
      nullptr}},
    kPlotOptions);
const std::vector<Name> kMonitorPlotOptions =
    joined({{"field", "the recorded field plotted against time", nullptr}}, kPlotOptions);

// A plot against time. (Strings swapped in: GCC 12 warns falsely, -Wrestrict,
// about assigning literals here.)
render::PlotSpec time_plot() {
  render::PlotSpec p;
  std::string label("time"), unit("s");
  p.x_label.swap(label);
  p.x_unit.swap(unit);
  return p;
}

// dda.plot{file = "plot.png", series = {{...}, ...}, title, x_label, ...} → path
int dda_plot(lua_State* L) {
  const Options o(L, 1, "dda.plot", kDdaPlotOptions);
  render::PlotSpec p = time_plot();
  read_plot_options(o, p);
  if (o.push("series") != LUA_TTABLE)
    fail("dda.plot: option 'series' must be a list of series {name =, x =, y =} or {monitor =, field =}");
  const int t = lua_gettop(L);
  for (lua_Unsigned i = 1; i <= lua_rawlen(L, t); ++i) {
    lua_rawgeti(L, t, static_cast<lua_Integer>(i));
    p.series.push_back(read_series(L, -1, msg("dda.plot series ", i)));
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  const auto path = in_out_dir(L, o.string("file"));
  create_parent(path, "dda.plot");
  p.validate();
  render::write_plot_png(p, path);
  lua_pushstring(L, path.c_str());
  return 1;
}

// monitor:plot{field = "sxx", file = "sxx.png", ...plot options} → path
int mon_plot(lua_State* L) {
  Handle* h = check_handle(L, 1, kMonitorType, "monitor:plot", "self");
  const Monitor& mon = h->model->monitor(h->id);
  const Options o(L, 2, "monitor:plot", kMonitorPlotOptions);
  const std::string field = o.string("field");
  const auto f = parse_field(field);
  if (!f) fail("monitor:plot: unknown field '", field, "'; known fields: ", field_list());
  std::size_t k = mon.fields.size();
  for (std::size_t i = 0; i < mon.fields.size(); ++i)
    if (mon.fields[i] == *f) k = i;
  if (k == mon.fields.size()) fail("monitor:plot: monitor '", mon.name, "' does not record '", field, "'");
  render::PlotSpec p = time_plot();
  p.title = mon.name;
  p.y_label = field;
  const bool stress = *f == Field::Sxx || *f == Field::Syy || *f == Field::Txy;
  const bool velocity = *f == Field::Vx || *f == Field::Vy;
  p.y_unit = stress ? "MPa" : velocity ? "m/s" : "m";
  p.y_scale = stress ? 1e-6 : 1;
  read_plot_options(o, p);
  p.series.push_back(render::Series{field, mon.times, mon.values[k], std::nullopt, 2});
  p.legend = o.has("legend") ? p.legend : render::LegendPosition::None;
  const auto path = in_out_dir(L, o.string("file"));
  create_parent(path, "monitor:plot");
  p.validate();
  render::write_plot_png(p, path);
  lua_pushstring(L, path.c_str());
  return 1;
}

}  // namespace

void register_render(lua_State* L) {
  static const Method model_methods[] = {
      {"frame", guarded<m_frame>, "m:frame{...} → the path written\nOne PNG frame of the model now.",
       kFrameCallOptions},
      {"frames", guarded<m_frames>,
       "m:frames{...} → Frames\nA numbered PNG sequence during the run (every N steps or every dt of simulated "
       "time), drawn on a worker thread; view and arrow scale fixed from the first frame, colours by each frame's "
       "own range unless one is declared; a movie at the end when ffmpeg is on the PATH.",
       kFramesOptions},
      {}};
  add_model_methods(L, model_methods, "Frames");
  static const Method methods[] = {
      {"count", guarded<fr_count>, "frames:count() → frames captured so far"},
      {"capture", guarded<fr_capture>, "frames:capture(): a frame now, due or not"},
      {"flush", guarded<fr_flush>, "frames:flush(): waits for the queued frames; raises their errors"},
      {"path", guarded<fr_path>, "frames:path([i]) → the file of frame i (from 0; default the last)"},
      {"folder", guarded<fr_folder>, "frames:folder() → the folder of the sequence"},
      {"active", guarded<fr_active>,
       "frames:active() → false (and the error) once a failing sequence stopped under on_error = \"continue\""},
      {"finish", guarded<fr_finish>,
       "frames:finish() → movie path or nil: writes the queued frames and makes the movie now (otherwise done when the "
       "model is closed or collected)"},
      {}};
  static const luaL_Reg meta[] = {{"__tostring", fr_tostring}, {nullptr, nullptr}};
  define_type(L, kFramesType, methods, meta);
  static const Method monitor_methods[] = {
      {"plot", guarded<mon_plot>, "monitor:plot{...} → the path written\nA recorded field against time, as PNG.",
       kMonitorPlotOptions},
      {}};
  add_methods(L, kMonitorType, monitor_methods);
}

void register_render_functions(lua_State* L) {
  static const Method functions[] = {
      {"plot", guarded<dda_plot>, "dda.plot{...} → the path written\nA line plot of series, as PNG.", kDdaPlotOptions},
      {}};
  set_methods(L, functions, "dda");
}

void attach_session_frames(lua_State* L, int model_idx) {
  const Session& s = session(L);
  if (s.frames_every <= 0) return;
  auto* box = static_cast<ModelBox*>(lua_touserdata(L, model_idx));
  render::SequenceOptions so;
  so.folder = s.out_dir / (s.models_created <= 1 ? std::string("frames") : msg("frames_", s.models_created));
  so.every_steps = s.frames_every;
  so.frame.field = render::parse_field(s.frames_field);
  so.frame.width = s.frames_width;
  so.frame.height = s.frames_height;
  so.from_step = s.frames_from;
  so.to_step = s.frames_to;
  if (s.frames_range_set) so.frame.range = render::ValueRange{s.frames_range[0], s.frames_range[1]};
  if (s.frames_view_set)
    so.frame.view = render::Box{s.frames_view[0], s.frames_view[1], s.frames_view[2], s.frames_view[3]};
  if (!s.frames_movie.empty()) {
    const std::filesystem::path movie = s.frames_movie;
    so.movie = movie.is_absolute() ? movie
               : s.models_created <= 1
                   ? s.out_dir / movie
                   : s.out_dir / (movie.stem().string() + msg("_", s.models_created) + movie.extension().string());
  }
  // dda run --restart: the continued model's frames are a sequence of their
  // own (its view and colours fixed afresh), beside the first run's.
  if (s.restart && s.restart->number == s.models_created) {
    const std::string from = msg("_from_step_", s.restart->world().step_count());
    so.folder += from;
    if (!so.movie.empty())
      so.movie = so.movie.parent_path() / (so.movie.stem().string() + from + so.movie.extension().string());
  }
  so.on_error = render::OnError::Continue;  // a command-line convenience never stops the run
  so.warn = [](const std::string& text) { warn(text); };
  try {
    so.frame.validate();  // (checked on the command line already)
    render_hook(*box->model).sequences.push_back(std::make_unique<render::FrameSequence>(std::move(so)));
  } catch (const Error& e) {  // the command line's options, not the script's line, are the cause
    fail("dda run --frames (the command line): ", e.what());
  }
}

}  // namespace dda::script

#else  // no renderer in this build

namespace dda::script {
void register_render(lua_State*) {}
void register_render_functions(lua_State*) {}
void attach_session_frames(lua_State*, int) {}
}  // namespace dda::script

#endif
