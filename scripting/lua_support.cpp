// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "lua_support.hpp"

#include "run_control.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <new>

namespace dda::script {

namespace {

lua_State* main_thread(lua_State* L) {
  lua_rawgeti(L, LUA_REGISTRYINDEX, LUA_RIDX_MAINTHREAD);
  lua_State* m = lua_tothread(L, -1);
  lua_pop(L, 1);
  return m;
}

void copy_message(char* out, std::size_t size, const char* text) {
  std::strncpy(out, text ? text : "(no message)", size - 1);
  out[size - 1] = '\0';
}

std::string number_text(double v) { return msg(v); }

// "m:add_block: " + message, from the running C function's name and the
// type of its first argument (the conventional receiver names used in every
// message of the Lua layer).
void prefix_call_name(lua_State* L, char* message, std::size_t size) {
  lua_Debug ar;
  if (!lua_getstack(L, 0, &ar) || !lua_getinfo(L, "n", &ar) || !ar.name) return;
  const char* receiver = nullptr;
  if (std::strcmp(ar.namewhat, "method") == 0 && lua_type(L, 1) == LUA_TUSERDATA) {
    const std::string type = type_of(L, 1);
    static const std::pair<const char*, const char*> names[] = {
        {"dda.Model", "m"},         {"dda.Block", "b"},        {"dda.BlockSet", "blocks"},   {"dda.EdgeSet", "edges"},
        {"dda.Monitor", "monitor"}, {"dda.PointLoad", "load"}, {"dda.Pressure", "pressure"}, {"dda.Hole", "hole"}};
    for (const auto& [t, r] : names)
      if (type == t) receiver = r;
  }
  char prefix[128];
  if (!receiver && std::strcmp(ar.namewhat, "field") == 0)
    std::snprintf(prefix, sizeof prefix, "dda.%s: ", ar.name);  // dda.model{...}
  else if (receiver)
    std::snprintf(prefix, sizeof prefix, "%s:%s: ", receiver, ar.name);
  else
    std::snprintf(prefix, sizeof prefix, "%s: ", ar.name);
  const std::size_t p = std::strlen(prefix), n = std::strlen(message);
  if (p + n + 1 > size) return;
  std::memmove(message + p, message, n + 1);
  std::memcpy(message, prefix, p);
}

}  // namespace

LuaCallError::~LuaCallError() {
  if (ref_ != LUA_NOREF && L_) luaL_unref(L_, LUA_REGISTRYINDEX, ref_);
}

int protected_call(lua_State* L, lua_CFunction f) {
  // Everything here is trivially destructible: luaL_error / lua_error below
  // longjmp out of this frame.
  char message[4096];
  message[0] = '\0';
  int ref = LUA_NOREF;
  bool failed = false;
  try {
    // The models this call takes (run_control.hpp) are let go when it
    // returns or throws, before any error is raised.
    const ApiCallScope holds;
    return f(L);
  } catch (const LuaCallError& e) {
    failed = true;
    ref = e.release();
    if (ref == LUA_NOREF) copy_message(message, sizeof message, e.what());
  } catch (const ScriptError& e) {
    failed = true;  // already names the call
    copy_message(message, sizeof message, e.what());
  } catch (const std::bad_alloc&) {
    failed = true;
    copy_message(message, sizeof message, "not enough memory");
  } catch (const std::exception& e) {
    // From the engine (dda::Error) or the library: name the call it came from.
    failed = true;
    copy_message(message, sizeof message, e.what());
    prefix_call_name(L, message, sizeof message);
  } catch (...) {
    failed = true;
    copy_message(message, sizeof message, "unknown C++ exception");
  }
  // Outside every catch block: now it is safe to raise.
  if (failed && ref != LUA_NOREF) {
    lua_rawgeti(L, LUA_REGISTRYINDEX, ref);
    luaL_unref(L, LUA_REGISTRYINDEX, ref);
    return lua_error(L);
  }
  return luaL_error(L, "%s", message);
}

void pcall(lua_State* L, int nargs, int nresults) {
  if (lua_pcall(L, nargs, nresults, 0) == LUA_OK) return;
  std::string text;
  if (lua_type(L, -1) == LUA_TSTRING || lua_type(L, -1) == LUA_TNUMBER)
    text = lua_tostring(L, -1);
  else
    text = msg("(error object is a ", luaL_typename(L, -1), " value)");
  lua_State* m = main_thread(L);
  const int ref = luaL_ref(L, LUA_REGISTRYINDEX);  // pops the error object
  throw LuaCallError(m, ref, std::move(text));
}

std::string type_of(lua_State* L, int idx) {
  if (lua_type(L, idx) == LUA_TUSERDATA && lua_getmetatable(L, idx)) {
    lua_getfield(L, -1, "__name");
    std::string name = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "userdata";
    lua_pop(L, 2);
    return name;
  }
  return luaL_typename(L, idx);
}

std::string function_where(lua_State* L, int idx) {
  lua_Debug ar;
  lua_pushvalue(L, idx);
  if (!lua_getinfo(L, ">S", &ar)) return "function";
  if (std::strcmp(ar.what, "C") == 0) return "C function";
  return msg("function at ", ar.short_src, ":", ar.linedefined);
}

// ---- plain values -------------------------------------------------------------

double check_number(lua_State* L, int idx, std::string_view call, std::string_view what) {
  if (lua_type(L, idx) != LUA_TNUMBER) fail(call, ": ", what, " must be a number, got ", type_of(L, idx));
  const double v = lua_tonumber(L, idx);
  if (!std::isfinite(v)) fail(call, ": ", what, " must be a finite number, got ", number_text(v));
  return v;
}

double opt_number(lua_State* L, int idx, double def, std::string_view call, std::string_view what) {
  if (lua_isnoneornil(L, idx)) return def;
  return check_number(L, idx, call, what);
}

long check_integer(lua_State* L, int idx, std::string_view call, std::string_view what) {
  const double v = check_number(L, idx, call, what);
  if (v != std::floor(v) || std::fabs(v) > 9e15)
    fail(call, ": ", what, " must be a whole number, got ", number_text(v));
  return static_cast<long>(v);
}

std::string check_string(lua_State* L, int idx, std::string_view call, std::string_view what) {
  if (lua_type(L, idx) != LUA_TSTRING) fail(call, ": ", what, " must be a string, got ", type_of(L, idx));
  std::size_t n = 0;
  const char* s = lua_tolstring(L, idx, &n);
  return std::string(s, n);
}

Vec2 check_point(lua_State* L, int idx, std::string_view call, std::string_view what) {
  idx = lua_absindex(L, idx);
  if (lua_type(L, idx) != LUA_TTABLE) fail(call, ": ", what, " must be a point {x, y}, got ", type_of(L, idx));
  if (lua_rawlen(L, idx) != 2) fail(call, ": ", what, " must be a point {x, y} with exactly two numbers");
  Vec2 p;
  for (int k = 0; k < 2; ++k) {
    lua_rawgeti(L, idx, k + 1);
    if (lua_type(L, -1) != LUA_TNUMBER || !std::isfinite(lua_tonumber(L, -1))) {
      const std::string t = type_of(L, -1);
      lua_pop(L, 1);
      fail(call, ": ", what, " must be a point {x, y} of finite numbers (entry ", k + 1, " is ", t, ")");
    }
    p[k] = lua_tonumber(L, -1);
    lua_pop(L, 1);
  }
  return p;
}

std::vector<Vec2> check_polygon(lua_State* L, int idx, std::string_view call, std::string_view what) {
  idx = lua_absindex(L, idx);
  if (lua_type(L, idx) != LUA_TTABLE)
    fail(call, ": ", what, " must be a list of points {{x, y}, ...}, got ", type_of(L, idx));
  const auto n = static_cast<int>(lua_rawlen(L, idx));
  if (n < 3) fail(call, ": ", what, " needs at least 3 points {x, y}, got ", n);
  std::vector<Vec2> pts;
  pts.reserve(n);
  for (int k = 1; k <= n; ++k) {
    lua_rawgeti(L, idx, k);
    try {
      pts.push_back(check_point(L, -1, call, msg(what, " point ", k)));
    } catch (...) {
      lua_pop(L, 1);
      throw;
    }
    lua_pop(L, 1);
  }
  return pts;
}

std::array<double, 4> check_quad(lua_State* L, int idx, std::string_view call, std::string_view what) {
  idx = lua_absindex(L, idx);
  if (lua_type(L, idx) != LUA_TTABLE || lua_rawlen(L, idx) != 4)
    fail(call, ": ", what, " must be {x1, y1, x2, y2}, got ", type_of(L, idx));
  std::array<double, 4> q{};
  for (int k = 0; k < 4; ++k) {
    lua_rawgeti(L, idx, k + 1);
    if (lua_type(L, -1) != LUA_TNUMBER || !std::isfinite(lua_tonumber(L, -1))) {
      lua_pop(L, 1);
      fail(call, ": ", what, " must be {x1, y1, x2, y2} of finite numbers (entry ", k + 1, ")");
    }
    q[k] = lua_tonumber(L, -1);
    lua_pop(L, 1);
  }
  return q;
}

std::vector<Vec2> box_polygon(const std::array<double, 4>& b) {
  const double x1 = std::min(b[0], b[2]), x2 = std::max(b[0], b[2]);
  const double y1 = std::min(b[1], b[3]), y2 = std::max(b[1], b[3]);
  return {Vec2(x1, y1), Vec2(x2, y1), Vec2(x2, y2), Vec2(x1, y2)};
}

double require_positive(double v, std::string_view call, std::string_view what) {
  if (!(v > 0)) fail(call, ": ", what, " must be positive, got ", number_text(v));
  return v;
}

double require_non_negative(double v, std::string_view call, std::string_view what) {
  if (!(v >= 0)) fail(call, ": ", what, " must be zero or positive, got ", number_text(v));
  return v;
}

// Optimal string alignment distance: insertions, deletions, substitutions
// and swaps of neighbours ("stpe" is one edit from "step").
int edit_distance(std::string_view a, std::string_view b) {
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<int>> d(n + 1, std::vector<int>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = static_cast<int>(i);
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = static_cast<int>(j);
  for (std::size_t i = 1; i <= n; ++i)
    for (std::size_t j = 1; j <= m; ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

// ---- option tables ---------------------------------------------------------------

Options::Options(lua_State* L, int idx, std::string call, Names known, bool allow_array)
    : L_(L), idx_(lua_absindex(L, idx)), call_(std::move(call)) {
  if (lua_type(L, idx_) != LUA_TTABLE) fail(call_, ": expected a table of options {...}, got ", type_of(L, idx_));
  const auto n = lua_rawlen(L, idx_);
  lua_pushnil(L);
  while (lua_next(L, idx_) != 0) {
    lua_pop(L, 1);  // value
    if (lua_type(L, -1) == LUA_TSTRING) {
      const std::string key = lua_tostring(L, -1);
      bool ok = false;
      for (const Name& k : known) ok = ok || key == k.name;
      if (!ok) {
        lua_pop(L, 1);
        std::string list, best;
        int best_d = 3;
        for (const Name& k : known) {
          list += list.empty() ? k.name : std::string(", ") + k.name;
          const int d = edit_distance(key, k.name);
          if (d < best_d) best_d = d, best = k.name;
        }
        fail(call_, ": unknown option '", key, "'", best.empty() ? "" : " (did you mean '" + best + "'?)",
             "; known options: ", list.empty() ? "none" : list);
      }
    } else if (allow_array && lua_isinteger(L, -1) && lua_tointeger(L, -1) >= 1 &&
               static_cast<lua_Unsigned>(lua_tointeger(L, -1)) <= n) {
      // array entry
    } else {
      const std::string t = lua_type(L, -1) == LUA_TNUMBER ? msg("[", lua_tostring(L, -1), "]") : type_of(L, -1);
      lua_pop(L, 1);
      fail(call_, ": unexpected entry ", t, " in the options table (options are named: {name = value, ...})");
    }
  }
}

std::string Options::what(const char* key) const { return msg(call_, "{", key, "}"); }

bool Options::has(const char* key) const {
  lua_pushstring(L_, key);
  const bool present = lua_rawget(L_, idx_) != LUA_TNIL;
  lua_pop(L_, 1);
  return present;
}

int Options::push(const char* key) const {
  lua_pushstring(L_, key);
  return lua_rawget(L_, idx_);
}

std::size_t Options::array_size() const { return lua_rawlen(L_, idx_); }

double Options::number(const char* key) const {
  if (push(key) == LUA_TNIL) {
    lua_pop(L_, 1);
    fail(call_, ": option '", key, "' is required");
  }
  try {
    const double v = check_number(L_, -1, call_, msg("option '", key, "'"));
    lua_pop(L_, 1);
    return v;
  } catch (...) {
    lua_pop(L_, 1);
    throw;
  }
}

double Options::number(const char* key, double def) const { return has(key) ? number(key) : def; }

double Options::positive(const char* key) const {
  return require_positive(number(key), call_, msg("option '", key, "'"));
}
double Options::positive(const char* key, double def) const { return has(key) ? positive(key) : def; }
double Options::non_negative(const char* key, double def) const {
  return has(key) ? require_non_negative(number(key), call_, msg("option '", key, "'")) : def;
}

long Options::integer(const char* key, long def) const {
  if (!has(key)) return def;
  push(key);
  try {
    const long v = check_integer(L_, -1, call_, msg("option '", key, "'"));
    lua_pop(L_, 1);
    return v;
  } catch (...) {
    lua_pop(L_, 1);
    throw;
  }
}

bool Options::boolean(const char* key, bool def) const {
  const int t = push(key);
  if (t == LUA_TNIL) {
    lua_pop(L_, 1);
    return def;
  }
  if (t != LUA_TBOOLEAN) {
    const std::string ty = type_of(L_, -1);
    lua_pop(L_, 1);
    fail(call_, ": option '", key, "' must be true or false, got ", ty);
  }
  const bool v = lua_toboolean(L_, -1);
  lua_pop(L_, 1);
  return v;
}

std::string Options::string(const char* key) const {
  if (!has(key)) fail(call_, ": option '", key, "' is required");
  push(key);
  try {
    std::string v = check_string(L_, -1, call_, msg("option '", key, "'"));
    lua_pop(L_, 1);
    return v;
  } catch (...) {
    lua_pop(L_, 1);
    throw;
  }
}

std::string Options::string(const char* key, const std::string& def) const { return has(key) ? string(key) : def; }

Vec2 Options::point(const char* key) const {
  if (push(key) == LUA_TNIL) {
    lua_pop(L_, 1);
    fail(call_, ": option '", key, "' is required (a point {x, y})");
  }
  try {
    const Vec2 v = check_point(L_, -1, call_, msg("option '", key, "'"));
    lua_pop(L_, 1);
    return v;
  } catch (...) {
    lua_pop(L_, 1);
    throw;
  }
}

Vec2 Options::point(const char* key, const Vec2& def) const { return has(key) ? point(key) : def; }

std::vector<Vec2> Options::polygon(const char* key) const {
  push(key);
  try {
    auto v = check_polygon(L_, -1, call_, msg("option '", key, "'"));
    lua_pop(L_, 1);
    return v;
  } catch (...) {
    lua_pop(L_, 1);
    throw;
  }
}

std::array<double, 4> Options::quad(const char* key) const {
  push(key);
  try {
    auto v = check_quad(L_, -1, call_, msg("option '", key, "'"));
    lua_pop(L_, 1);
    return v;
  } catch (...) {
    lua_pop(L_, 1);
    throw;
  }
}

int one_of(const Options& o, std::initializer_list<const char*> keys) {
  int found = -1, i = 0, count = 0;
  std::string list;
  for (const char* k : keys) {
    list += list.empty() ? std::string("'") + k + "'" : std::string(", '") + k + "'";
    if (o.has(k)) found = i, ++count;
    ++i;
  }
  if (count != 1) fail(o.call(), ": give exactly one of ", list, count == 0 ? " (none given)" : " (several given)");
  return found;
}

// ---- registry references ------------------------------------------------------------

LuaRef::LuaRef(lua_State* L, int idx) : main_(main_thread(L)) {
  lua_pushvalue(L, idx);
  ref_ = luaL_ref(L, LUA_REGISTRYINDEX);
}

LuaRef& LuaRef::operator=(LuaRef&& o) noexcept {
  if (this != &o) {
    reset();
    main_ = o.main_;
    ref_ = o.ref_;
    o.ref_ = LUA_NOREF;
  }
  return *this;
}

void LuaRef::reset() {
  if (ref_ != LUA_NOREF && main_) luaL_unref(main_, LUA_REGISTRYINDEX, ref_);
  ref_ = LUA_NOREF;
}

// ---- histories ---------------------------------------------------------------------------

TimeInput TimeInput::parse(lua_State* L, int idx, std::string_view call, std::string_view what) {
  idx = lua_absindex(L, idx);
  TimeInput h;
  h.what_ = msg(call, " ", what);
  switch (lua_type(L, idx)) {
    case LUA_TNUMBER:
      h.value_ = check_number(L, idx, call, what);
      return h;
    case LUA_TFUNCTION:
      h.kind_ = Kind::Function;
      h.fn_ = LuaRef(L, idx);
      h.where_ = function_where(L, idx);
      return h;
    case LUA_TTABLE: {
      h.kind_ = Kind::Table;
      const auto n = static_cast<int>(lua_rawlen(L, idx));
      if (n == 0) fail(call, ": ", what, " must not be an empty table (give {{t, value}, ...})");
      for (int k = 1; k <= n; ++k) {
        lua_rawgeti(L, idx, k);
        Vec2 p;
        try {
          p = check_point(L, -1, call, msg(what, " entry ", k, " {t, value}"));
        } catch (...) {
          lua_pop(L, 1);
          throw;
        }
        lua_pop(L, 1);
        if (!h.t_.empty() && p.x() < h.t_.back())
          fail(call, ": ", what, " times must not decrease (entry ", k, " has t = ", p.x(), " after t = ", h.t_.back(),
               ")");
        h.t_.push_back(p.x());
        h.v_.push_back(p.y());
      }
      return h;
    }
    default:
      fail(call, ": ", what, " must be a number, a table of {t, value} pairs or a function of t, got ",
           type_of(L, idx));
  }
}

double TimeInput::at(lua_State* L, double t) const {
  switch (kind_) {
    case Kind::Constant:
      return value_;
    case Kind::Table: {
      if (t <= t_.front()) return v_.front();
      if (t >= t_.back()) return v_.back();
      const auto it = std::upper_bound(t_.begin(), t_.end(), t);  // first time > t
      const auto i = static_cast<std::size_t>(it - t_.begin());
      const double t0 = t_[i - 1], t1 = t_[i];
      const double s = (t - t0) / (t1 - t0);
      return v_[i - 1] + s * (v_[i] - v_[i - 1]);
    }
    case Kind::Function: {
      if (!lua_checkstack(L, 3)) throw ScriptError(msg(what_, ": Lua stack overflow"));
      fn_.push(L);
      lua_pushnumber(L, t);
      pcall(L, 1, 1);
      if (lua_type(L, -1) != LUA_TNUMBER || !std::isfinite(lua_tonumber(L, -1))) {
        const std::string got = lua_type(L, -1) == LUA_TNUMBER ? msg(lua_tonumber(L, -1)) : type_of(L, -1);
        lua_pop(L, 1);
        fail(what_, ": the ", where_, " returned ", got, " at t = ", t, " (expected a finite number)");
      }
      const double v = lua_tonumber(L, -1);
      lua_pop(L, 1);
      return v;
    }
  }
  return 0;
}

dda::History TimeInput::engine_history() const {
  if (kind_ == Kind::Constant) return dda::History::constant(value_);
  if (kind_ == Kind::Function) throw ScriptError(msg(what_, ": a function of t cannot be handed to the engine"));
  std::vector<std::pair<double, double>> points;
  for (std::size_t i = 0; i < t_.size(); ++i) {
    // The engine wants increasing times; a jump (two equal times) becomes a
    // very steep ramp.
    double t = t_[i];
    if (!points.empty() && t <= points.back().first)
      t = std::nextafter(points.back().first, std::numeric_limits<double>::infinity());
    points.emplace_back(t, v_[i]);
  }
  return dda::History(std::move(points), what_);
}

void TimeInput::check_loaded(const LoadCheck& check, const std::string& name) {
  what_ = printable(what_), where_ = printable(where_);
  if (kind_ == Kind::Constant) check.finite(value_, name, "'s value");
  if (kind_ != Kind::Table) return;
  check.require(!t_.empty() && t_.size() == v_.size(), name, "'s table has ", t_.size(), " times and ", v_.size(),
                " values");
  for (std::size_t i = 0; i < t_.size(); ++i)
    check.require(std::isfinite(t_[i]) && std::isfinite(v_[i]) && (i == 0 || t_[i] >= t_[i - 1]), name,
                  "'s table point ", i + 1, " is not finite or goes back in time");
}

void VecTimeInput::check_loaded(const LoadCheck& check, const std::string& name) {
  what_ = printable(what_), where_ = printable(where_);
  x_.check_loaded(check, name + " x");
  y_.check_loaded(check, name + " y");
}

VecTimeInput VecTimeInput::function(lua_State* L, int idx, std::string_view call, std::string_view what) {
  if (lua_type(L, idx) != LUA_TFUNCTION) fail(call, ": ", what, " must be a function, got ", type_of(L, idx));
  VecTimeInput h;
  h.fn_ = LuaRef(L, idx);
  h.what_ = msg(call, " ", what);
  h.where_ = function_where(L, idx);
  return h;
}

Vec2 VecTimeInput::at(lua_State* L, double t) const {
  if (!fn_.valid()) return Vec2(x_.at(L, t), y_.at(L, t));
  if (!lua_checkstack(L, 3)) throw ScriptError(msg(what_, ": Lua stack overflow"));
  fn_.push(L);
  lua_pushnumber(L, t);
  pcall(L, 1, 2);
  Vec2 v;
  for (int k = 0; k < 2; ++k) {
    const int i = -2 + k;
    if (lua_type(L, i) != LUA_TNUMBER || !std::isfinite(lua_tonumber(L, i))) {
      const std::string got = lua_type(L, i) == LUA_TNUMBER ? msg(lua_tonumber(L, i)) : type_of(L, i);
      lua_pop(L, 2);
      fail(what_, ": the ", where_, " returned ", got, " as its ", k == 0 ? "first" : "second", " value at t = ", t,
           " (expected two finite numbers x, y)");
    }
    v[k] = lua_tonumber(L, i);
  }
  lua_pop(L, 2);
  return v;
}

}  // namespace dda::script
