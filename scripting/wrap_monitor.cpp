// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// dda.Monitor: a material point whose fields are recorded every N steps into
// memory and into <out>/<name>.csv (header line, one row per recorded step,
// flushed row by row).
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <mutex>
#include <system_error>

#include "session.hpp"
#include "wrap.hpp"

namespace dda::script {

namespace {

bool valid_name(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) return false;
  return s != "." && s != "..";
}

constexpr Name kMonitorOptions[] = {
    {"at", "{x, y}: the material point followed (it moves with its block)", nullptr},
    {"fields", "the fields recorded, e.g. {\"sxx\", \"vx\", \"vy\"} (the monitor fields: lua_api.md)", nullptr},
    {"every", "record every this many steps", "1"},
    {"name", "its name, and its CSV file's: <out>/<name>.csv", "\"monitor1\", \"monitor2\", ..."},
    {"block", "the Block the point belongs to (when `at` lies on several)", "the block containing `at`"},
    {"csv", "write the CSV file (false: in memory only)", "true"}};

// m:monitor{at = {x, y}, fields = {"sxx", ...}, every = 1, name = "centre", block = b, csv = true} → Monitor
int m_monitor(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:monitor");
  check_not_busy(m, "m:monitor");
  Session& session_ = session(L);
  const Options o(L, 2, "m:monitor", kMonitorOptions);
  auto mon = std::make_unique<Monitor>();
  mon->point = o.point("at");
  BlockId b;
  if (o.has("block")) {
    o.push("block");
    b = check_block(L, -1, &m, "m:monitor", "option 'block'");
    lua_pop(L, 1);
  } else {
    const auto found = m.block_at(mon->point);
    if (!found)
      fail("m:monitor: no block at (", mon->point.x(), ", ", mon->point.y(),
           "); give block = ... or a point inside a block");
    b = *found;
  }
  // fields
  if (o.push("fields") != LUA_TTABLE) {
    lua_pop(L, 1);
    fail("m:monitor: option 'fields' is required: a list of field names from ", field_list());
  }
  const int ft = lua_gettop(L);
  const auto nf = static_cast<int>(lua_rawlen(L, ft));
  if (nf == 0) fail("m:monitor: option 'fields' is empty; choose from ", field_list());
  for (int k = 1; k <= nf; ++k) {
    lua_rawgeti(L, ft, k);
    if (lua_type(L, -1) != LUA_TSTRING)
      fail("m:monitor: option 'fields' entry ", k, " must be a field name, got ", type_of(L, -1));
    const std::string name = lua_tostring(L, -1);
    lua_pop(L, 1);
    const auto f = parse_field(name);
    if (!f) fail("m:monitor: unknown field '", name, "' in option 'fields'; known fields: ", field_list());
    for (Field g : mon->fields)
      if (g == *f) fail("m:monitor: field '", name, "' is listed twice in option 'fields'");
    mon->fields.push_back(*f);
  }
  lua_pop(L, 1);
  const long every = o.integer("every", 1);
  if (every < 1) fail("m:monitor: option 'every' must be at least 1, got ", every);
  mon->every = static_cast<int>(every);
  mon->name = o.string("name", msg("monitor", session_.files.size() + 1));
  if (!valid_name(mon->name))
    fail("m:monitor: option 'name' must be a plain file name (letters, digits, '_', '-', '.'), got \"", mon->name,
         "\"");

  if (o.boolean("csv", true)) {
    std::error_code ec;
    std::filesystem::create_directories(session_.out_dir, ec);
    if (ec) fail("m:monitor: cannot create the output folder '", session_.out_dir.string(), "': ", ec.message());
    mon->path = session_.out_dir / (mon->name + ".csv");
    const std::string key = std::filesystem::weakly_canonical(mon->path, ec).string();
    if (session_.files.count(key))
      fail("m:monitor: another monitor already writes ", mon->path.string(),
           " in this run; give this one another name");
    std::string header = "step,time";
    for (Field f : mon->fields) header.append(",").append(field_name(f));
    // dda run --restart: the rows of the run being continued, put back up to
    // the checkpoint's step when this model restarts (ScriptModel::restore).
    if (session_.restart && session_.restart->number == m.number) {
      std::ifstream old(mon->path);
      std::string line;
      while (std::getline(old, line)) mon->previous_lines.push_back(line);
      if (mon->previous_lines.empty() || mon->previous_lines[0] != header) mon->previous_lines.clear();
    }
    try {
      mon->file = AppendFile(mon->path, AppendFile::Mode::Truncate);
      mon->file.append(header + "\n");
    } catch (const Error& e) {
      fail("m:monitor: ", e.what());
    }
    session_.files.insert(key);
  } else {
    session_.files.insert(msg("(memory) ", mon->name, " ", session_.files.size()));
  }
  mon->tracked = m.world().add_tracked_point(b, mon->point);
  mon->values.resize(mon->fields.size());
  const int id = m.add_monitor(std::move(mon));
  push_monitor(L, 1, id);
  return 1;
}

// m:monitors() → list of every monitor of the model
int m_monitors(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:monitors");
  lua_createtable(L, m.monitor_count(), 0);
  for (int i = 0; i < m.monitor_count(); ++i) {
    push_monitor(L, 1, i);
    lua_rawseti(L, -2, i + 1);
  }
  return 1;
}

// ---- dda.Monitor --------------------------------------------------------------------------------

struct Self {
  ScriptModel* model;
  Monitor* mon;
};
Self self_monitor(lua_State* L, const char* call) {
  Handle* h = check_handle(L, 1, kMonitorType, call, "self");
  if (h->id < 0 || h->id >= h->model->monitor_count()) fail(call, ": attempt to use an invalid monitor");
  return {h->model, &h->model->monitor(h->id)};
}

// The column of `field` (argument idx) in this monitor.
std::size_t field_arg(lua_State* L, int idx, const Monitor& mon, const char* call) {
  const std::string name = check_string(L, idx, call, "argument 1 (field)");
  const auto f = parse_field(name);
  if (!f) fail(call, ": unknown field '", name, "'; known fields: ", field_list());
  for (std::size_t k = 0; k < mon.fields.size(); ++k)
    if (mon.fields[k] == *f) return k;
  std::string have;
  for (Field g : mon.fields) have += have.empty() ? field_name(g) : std::string(", ") + field_name(g);
  fail(call, ": monitor '", mon.name, "' does not record '", name, "' (it records ", have, ")");
}

void push_numbers(lua_State* L, const std::vector<double>& v) {
  lua_createtable(L, static_cast<int>(v.size()), 0);
  for (std::size_t i = 0; i < v.size(); ++i) {
    lua_pushnumber(L, v[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

int mon_name(lua_State* L) {
  lua_pushstring(L, self_monitor(L, "monitor:name").mon->name.c_str());
  return 1;
}
int mon_file(lua_State* L) {
  const Self s = self_monitor(L, "monitor:file");
  if (s.mon->path.empty())
    lua_pushnil(L);
  else
    lua_pushstring(L, s.mon->path.c_str());
  return 1;
}
int mon_fields(lua_State* L) {
  const Self s = self_monitor(L, "monitor:fields");
  lua_createtable(L, static_cast<int>(s.mon->fields.size()), 0);
  for (std::size_t k = 0; k < s.mon->fields.size(); ++k) {
    lua_pushstring(L, field_name(s.mon->fields[k]));
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
  return 1;
}
int mon_count(lua_State* L) {
  lua_pushinteger(L, static_cast<lua_Integer>(self_monitor(L, "monitor:count").mon->times.size()));
  return 1;
}
int mon_times(lua_State* L) {
  push_numbers(L, self_monitor(L, "monitor:times").mon->times);
  return 1;
}
int mon_steps(lua_State* L) {
  const Self s = self_monitor(L, "monitor:steps");
  lua_createtable(L, static_cast<int>(s.mon->steps.size()), 0);
  for (std::size_t i = 0; i < s.mon->steps.size(); ++i) {
    lua_pushinteger(L, s.mon->steps[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}
// monitor:series("sxx") → {v1, v2, ...} (one per recorded row)
int mon_series(lua_State* L) {
  const Self s = self_monitor(L, "monitor:series");
  push_numbers(L, s.mon->values[field_arg(L, 2, *s.mon, "monitor:series")]);
  return 1;
}
// monitor:value("sxx") → the value now (not necessarily recorded)
int mon_value(lua_State* L) {
  const Self s = self_monitor(L, "monitor:value");
  const std::string name = check_string(L, 2, "monitor:value", "argument 1 (field)");
  const auto f = parse_field(name);
  if (!f) fail("monitor:value: unknown field '", name, "'; known fields: ", field_list());
  lua_pushnumber(L, s.model->field_value(*s.mon, *f));
  return 1;
}
// monitor:last("sxx") → last recorded value, its time (nil when nothing recorded)
int mon_last(lua_State* L) {
  const Self s = self_monitor(L, "monitor:last");
  const std::size_t k = field_arg(L, 2, *s.mon, "monitor:last");
  if (s.mon->times.empty()) {
    lua_pushnil(L);
    return 1;
  }
  lua_pushnumber(L, s.mon->values[k].back());
  lua_pushnumber(L, s.mon->times.back());
  return 2;
}
// The vector fields a monitor's pairs of columns make: their peaks are of
// the magnitude, sqrt(x² + y²).
struct VectorField {
  const char* name;
  Field x, y;
};
constexpr VectorField kVectorFields[] = {{"velocity", Field::Vx, Field::Vy}, {"displacement", Field::Ux, Field::Uy}};

const VectorField* find_vector_field(const std::string& name) {
  for (const VectorField& v : kVectorFields)
    if (name == v.name) return &v;
  return nullptr;
}

// The column of `f` in this monitor, or fails naming what it records.
std::size_t column(const Monitor& mon, Field f, const char* call, const std::string& asked) {
  for (std::size_t k = 0; k < mon.fields.size(); ++k)
    if (mon.fields[k] == f) return k;
  std::string have;
  for (Field g : mon.fields) have += have.empty() ? field_name(g) : std::string(", ") + field_name(g);
  fail(call, ": monitor '", mon.name, "' does not record '", field_name(f), "', which '", asked, "' needs (it records ",
       have, "; add it to the monitor's fields)");
}

// The row of the largest magnitude of a vector field: pushes |v|, its time,
// and the two components then (nil when nothing is recorded).
int vector_peak(lua_State* L, const Self& s, const VectorField& v, const char* call) {
  const auto& x = s.mon->values[column(*s.mon, v.x, call, v.name)];
  const auto& y = s.mon->values[column(*s.mon, v.y, call, v.name)];
  if (x.empty()) {
    lua_pushnil(L);
    return 1;
  }
  std::size_t best = 0;
  double best_magnitude = std::hypot(x[0], y[0]);
  for (std::size_t i = 1; i < x.size(); ++i)
    if (const double magnitude = std::hypot(x[i], y[i]); magnitude > best_magnitude)
      best = i, best_magnitude = magnitude;
  lua_pushnumber(L, best_magnitude);
  lua_pushnumber(L, s.mon->times[best]);
  lua_pushnumber(L, x[best]);
  lua_pushnumber(L, y[best]);
  return 4;
}

enum class Extreme { Max, Min, Peak };

int extreme(lua_State* L, const char* call, Extreme mode) {
  const Self s = self_monitor(L, call);
  if (mode != Extreme::Min && lua_type(L, 2) == LUA_TSTRING)
    if (const VectorField* v = find_vector_field(lua_tostring(L, 2))) return vector_peak(L, s, *v, call);
  const std::size_t k = field_arg(L, 2, *s.mon, call);
  const auto& v = s.mon->values[k];
  if (v.empty()) {
    lua_pushnil(L);
    return 1;
  }
  std::size_t best = 0;
  for (std::size_t i = 1; i < v.size(); ++i) {
    const bool better = mode == Extreme::Max   ? v[i] > v[best]
                        : mode == Extreme::Min ? v[i] < v[best]
                                               : std::fabs(v[i]) > std::fabs(v[best]);
    if (better) best = i;
  }
  lua_pushnumber(L, v[best]);
  lua_pushnumber(L, s.mon->times[best]);
  return 2;
}
// monitor:max("sxx") → value, time; monitor:min; monitor:peak (largest |value|)
int mon_max(lua_State* L) { return extreme(L, "monitor:max", Extreme::Max); }
int mon_min(lua_State* L) { return extreme(L, "monitor:min", Extreme::Min); }
int mon_peak(lua_State* L) { return extreme(L, "monitor:peak", Extreme::Peak); }
// monitor:ppv() → the peak particle velocity, its time, vx, vy then
int mon_ppv(lua_State* L) {
  const Self s = self_monitor(L, "monitor:ppv");
  return vector_peak(L, s, kVectorFields[0], "monitor:ppv");
}
// monitor:row(i) → {step = , time = , sxx = , ...}; i from 1, negative from the end
int mon_row(lua_State* L) {
  const Self s = self_monitor(L, "monitor:row");
  long i = check_integer(L, 2, "monitor:row", "argument 1 (row)");
  const long n = static_cast<long>(s.mon->times.size());
  if (i < 0) i = n + 1 + i;
  if (i < 1 || i > n) {
    lua_pushnil(L);
    return 1;
  }
  lua_createtable(L, 0, static_cast<int>(s.mon->fields.size()) + 2);
  lua_pushinteger(L, s.mon->steps[i - 1]);
  lua_setfield(L, -2, "step");
  lua_pushnumber(L, s.mon->times[i - 1]);
  lua_setfield(L, -2, "time");
  for (std::size_t k = 0; k < s.mon->fields.size(); ++k) {
    lua_pushnumber(L, s.mon->values[k][i - 1]);
    lua_setfield(L, -2, field_name(s.mon->fields[k]));
  }
  return 1;
}
int mon_block(lua_State* L) {
  const Self s = self_monitor(L, "monitor:block");
  push_model_of(L, 1);
  push_block(L, -1, s.model->world().tracked_block(s.mon->tracked));
  return 1;
}
// monitor:position() → x, y of the material point now
int mon_position(lua_State* L) {
  const Self s = self_monitor(L, "monitor:position");
  const Vec2 p = s.model->world().tracked_position(s.mon->tracked);
  lua_pushnumber(L, p.x());
  lua_pushnumber(L, p.y());
  return 2;
}
int mon_tostring(lua_State* L) {
  auto* h = static_cast<Handle*>(luaL_checkudata(L, 1, kMonitorType));
  if (!h->model || h->model->closed() || h->id >= h->model->monitor_count()) {
    lua_pushliteral(L, "dda.Monitor (invalid)");
    return 1;
  }
  std::string text;
  {
    std::lock_guard hold(h->model->control().lock);  // between two steps of a background run
    const Monitor& mon = h->model->monitor(h->id);
    text = msg("dda.Monitor '", mon.name, "' (", mon.times.size(), " rows)");
  }
  lua_pushstring(L, text.c_str());
  return 1;
}

}  // namespace

void register_monitor(lua_State* L) {
  static const Method model_methods[] = {
      {"monitor", guarded<m_monitor>,
       "m:monitor{...} → Monitor\nFollows a material point: its fields every `every` steps into memory and into "
       "<out>/<name>.csv (a header, one whole row per record).",
       kMonitorOptions},
      {"monitors", guarded<m_monitors>, "m:monitors() → list of every monitor of the model"},
      {}};
  add_model_methods(L, model_methods, "Monitors");
  static const Method methods[] = {
      {"name", guarded<mon_name>, "monitor:name() → its name"},
      {"file", guarded<mon_file>, "monitor:file() → the path of its CSV file (nil with csv = false)"},
      {"fields", guarded<mon_fields>, "monitor:fields() → {\"sxx\", ...}: the fields it records"},
      {"count", guarded<mon_count>, "monitor:count() → the number of recorded rows"},
      {"times", guarded<mon_times>, "monitor:times() → {t1, t2, ...}: the time of each row (s)"},
      {"steps", guarded<mon_steps>, "monitor:steps() → {n1, n2, ...}: the step of each row"},
      {"series", guarded<mon_series>, "monitor:series(\"sxx\") → {v1, v2, ...} (one per recorded row)"},
      {"value", guarded<mon_value>, "monitor:value(\"sxx\") → the value now (not necessarily recorded)"},
      {"last", guarded<mon_last>, "monitor:last(\"sxx\") → last recorded value, its time (nil when nothing recorded)"},
      {"max", guarded<mon_max>,
       "monitor:max(\"sxx\") → the largest recorded value, its time; of a vector field (\"velocity\", "
       "\"displacement\") as monitor:peak"},
      {"min", guarded<mon_min>, "monitor:min(\"sxx\") → the smallest recorded value, its time"},
      {"peak", guarded<mon_peak>,
       "monitor:peak(\"sxx\") → the recorded value of largest |value|, its time; monitor:peak(\"velocity\") or "
       "(\"displacement\") → the largest magnitude sqrt(x² + y²) of that vector (the monitor records both "
       "components: vx, vy or ux, uy), its time, and the two components then"},
      {"ppv", guarded<mon_ppv>,
       "monitor:ppv() → the peak particle velocity: the largest recorded sqrt(vx² + vy²) (m/s), its time, and vx, vy "
       "then; the monitor records vx and vy (the largest component alone: monitor:peak(\"vx\"))"},
      {"row", guarded<mon_row>, "monitor:row(i) → {step = , time = , sxx = , ...}; i from 1, negative from the end"},
      {"block", guarded<mon_block>, "monitor:block() → the Block its material point belongs to"},
      {"position", guarded<mon_position>, "monitor:position() → x, y of the material point now"},
      {}};
  static const luaL_Reg meta[] = {{"__tostring", mon_tostring}, {nullptr, nullptr}};
  define_type(L, kMonitorType, methods, meta);
}

}  // namespace dda::script
