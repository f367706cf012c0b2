// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Loads and constraints: m:point_load{...} (dda.PointLoad), m:fix(x, y), and
// dda.Pressure (made by edges:pressure(p)).
#include "wrap.hpp"

namespace dda::script {

namespace {

// Reads the force of a point load from an options table:
//   force = {fx, fy} | force = function(t) return fx, fy end
//   | fx = h, fy = h                       (each h a number, {{t, v}, ...} or function of t)
//   | direction = {dx, dy}, magnitude = h  (the paper's FHI: direction × h(t))
ForceInput read_force(const Options& o) {
  lua_State* L = o.state();
  ForceInput in;
  const bool components = o.has("fx") || o.has("fy");
  const bool along = o.has("direction") || o.has("magnitude");
  if (int(o.has("force")) + int(components) + int(along) != 1)
    fail(o.call(),
         ": give the force once: force = {fx, fy}, force = function(t) return fx, fy end, "
         "fx = ..., fy = ..., or direction = {dx, dy}, magnitude = ...");
  if (along) {
    const Vec2 d = o.point("direction");
    if (d.norm() == 0) fail(o.call(), ": option 'direction' must not be zero");
    if (!o.has("magnitude")) fail(o.call(), ": option 'magnitude' is required with 'direction'");
    in.along = true;
    in.direction = d.normalized();
    o.push("magnitude");
    in.magnitude = TimeInput::parse(L, -1, o.call(), "option 'magnitude'");
    lua_pop(L, 1);
    return in;
  }
  if (components) {
    TimeInput x, y;
    if (o.has("fx")) {
      o.push("fx");
      x = TimeInput::parse(L, -1, o.call(), "option 'fx'");
      lua_pop(L, 1);
    }
    if (o.has("fy")) {
      o.push("fy");
      y = TimeInput::parse(L, -1, o.call(), "option 'fy'");
      lua_pop(L, 1);
    }
    in.xy = VecTimeInput(std::move(x), std::move(y));
    return in;
  }
  const int t = o.push("force");
  if (t == LUA_TFUNCTION) {
    in.xy = VecTimeInput::function(L, -1, o.call(), "option 'force'");
    lua_pop(L, 1);
    return in;
  }
  if (t != LUA_TTABLE) {
    const std::string ty = type_of(L, -1);
    lua_pop(L, 1);
    fail(o.call(), ": option 'force' must be {fx, fy} or a function of t returning fx, fy; got ", ty);
  }
  Vec2 f;
  try {
    f = check_point(L, -1, o.call(), "option 'force' {fx, fy}");
  } catch (...) {
    lua_pop(L, 1);
    throw;
  }
  lua_pop(L, 1);
  in.xy = VecTimeInput::constant(f);
  return in;
}

BlockId block_for_point(lua_State* L, const Options& o, ScriptModel& m, const Vec2& p) {
  if (o.has("block")) {
    o.push("block");
    const BlockId b = check_block(L, -1, &m, o.call(), "option 'block'");
    lua_pop(L, 1);
    return b;
  }
  const auto b = m.block_at(p);
  if (!b) fail(o.call(), ": no block at (", p.x(), ", ", p.y(), "); give block = ... or a point inside a block");
  return *b;
}

// The force's options (read_force), a history each: a number, {{t, v}, ...}
// (linear between) or a function of t.
constexpr Name kForceOptions[] = {
    {"force", "{fx, fy} (N/m), or a function(t) returning fx, fy; or give fx, fy, or direction and magnitude", "—"},
    {"fx", "x force (N/m): a number, {{t, fx}, ...} or a function(t)", "0"},
    {"fy", "y force (N/m), as fx", "0"},
    {"direction", "{dx, dy}: the force's direction (the paper's FHI: direction × magnitude(t))", "—"},
    {"magnitude", "the force along `direction` (N/m), as fx", "—"}};
const std::vector<Name> kPointLoadOptions = [] {
  std::vector<Name> n = {{"at", "{x, y}: the material point the load acts at (it moves with its block)", nullptr},
                         {"block", "the Block it acts on (when `at` lies on several)", "the block containing `at`"}};
  n.insert(n.end(), std::begin(kForceOptions), std::end(kForceOptions));
  return n;
}();

// m:point_load{at = {x, y}, block = b, force = ... | fx = ..., fy = ...} → PointLoad
int m_point_load(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:point_load");
  check_not_busy(m, "m:point_load");
  const Options o(L, 2, "m:point_load", kPointLoadOptions);
  const Vec2 at = o.point("at");
  const BlockId b = block_for_point(L, o, m, at);
  ForceInput force = read_force(o);
  const int id = m.add_point_load(b, at, std::move(force), L);
  push_point_load(L, 1, id);
  return 1;
}

// m:fix(x, y [, block]) or m:fix{x, y} → adds a fixed point (a stiff spring
// holding that material point where it starts).
int m_fix(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:fix");
  check_not_busy(m, "m:fix");
  Vec2 p;
  int block_arg = 4;
  if (lua_type(L, 2) == LUA_TTABLE) {
    p = check_point(L, 2, "m:fix", "argument 1 (point)");
    block_arg = 3;
  } else {
    p = Vec2(check_number(L, 2, "m:fix", "argument 1 (x)"), check_number(L, 3, "m:fix", "argument 2 (y)"));
  }
  BlockId b;
  if (!lua_isnoneornil(L, block_arg)) {
    b = check_block(L, block_arg, &m, "m:fix", "the block argument");
  } else {
    const auto found = m.block_at(p);
    if (!found) fail("m:fix: no block at (", p.x(), ", ", p.y(), ")");
    b = *found;
  }
  m.add_fixed_point(b, p);
  push_block(L, 1, b);
  return 1;
}

// ---- dda.PointLoad ----------------------------------------------------------------------------

Handle* self_load(lua_State* L, const char* call) {
  Handle* h = check_handle(L, 1, kPointLoadType, call, "self");
  if (h->id < 0 || h->id >= h->model->point_load_count()) fail(call, ": attempt to use an invalid point load");
  return h;
}

// load:set(fx, fy) or load:set{force = ... | fx = ..., fy = ...}
int pl_set(lua_State* L) {
  Handle* h = self_load(L, "load:set");
  check_not_busy(*h->model, "load:set");
  ForceInput force;
  if (lua_type(L, 2) == LUA_TTABLE) {
    const Options o(L, 2, "load:set", kForceOptions);
    force = read_force(o);
  } else {
    force.xy = VecTimeInput::constant(
        Vec2(check_number(L, 2, "load:set", "argument 1 (fx)"), check_number(L, 3, "load:set", "argument 2 (fy)")));
  }
  h->model->set_point_load(h->id, std::move(force), L);
  return 0;
}

// load:force() → fx, fy applied in the last (or next) step
int pl_force(lua_State* L) {
  Handle* h = self_load(L, "load:force");
  const Vec2 f = h->model->point_load_value(h->id, L);
  lua_pushnumber(L, f.x());
  lua_pushnumber(L, f.y());
  return 2;
}

int pl_block(lua_State* L) {
  Handle* h = self_load(L, "load:block");
  push_model_of(L, 1);
  push_block(L, -1, h->model->point_load(h->id).block);
  return 1;
}

int pl_tostring(lua_State* L) {
  auto* h = static_cast<Handle*>(luaL_checkudata(L, 1, kPointLoadType));
  lua_pushfstring(L, "dda.PointLoad %d", static_cast<int>(h->id + 1));
  return 1;
}

// ---- dda.Pressure -------------------------------------------------------------------------------

Handle* self_pressure(lua_State* L, const char* call) {
  Handle* h = check_handle(L, 1, kPressureType, call, "self");
  if (h->id < 0 || h->id >= h->model->pressure_count()) fail(call, ": attempt to use an invalid pressure");
  return h;
}

// pressure:set(p): a number, {{t, p}, ...} or function(t)
int pr_set(lua_State* L) {
  Handle* h = self_pressure(L, "pressure:set");
  check_not_busy(*h->model, "pressure:set");
  TimeInput p = TimeInput::parse(L, 2, "pressure:set", "argument 1 (pressure)");
  h->model->set_pressure(h->id, std::move(p), L);
  return 0;
}

// pressure:value() → the pressure applied in the last (or next) step (Pa)
int pr_value(lua_State* L) {
  Handle* h = self_pressure(L, "pressure:value");
  lua_pushnumber(L, h->model->pressure_value(h->id, L));
  return 1;
}

int pr_edges(lua_State* L) {
  Handle* h = self_pressure(L, "pressure:edges");
  push_model_of(L, 1);
  push_edgeset(L, -1, h->model->pressure(h->id).edges);
  return 1;
}

int pr_tostring(lua_State* L) {
  auto* h = static_cast<Handle*>(luaL_checkudata(L, 1, kPressureType));
  lua_pushfstring(L, "dda.Pressure %d", static_cast<int>(h->id + 1));
  return 1;
}

}  // namespace

void register_loads(lua_State* L) {
  static const Method model_methods[] = {
      {"point_load", guarded<m_point_load>,
       "m:point_load{...} → PointLoad\nA force at a material point; each component a number, a table {{t, v}, ...} "
       "(linear between, evaluated at each step's end) or a function of t (evaluated once per step).",
       kPointLoadOptions},
      {"fix", guarded<m_fix>,
       "m:fix(x, y [, block]) or m:fix{x, y} → adds a fixed point (a stiff spring holding that material point where it "
       "starts)."},
      {}};
  add_model_methods(L, model_methods, "Loads and fixed points");
  static const Method pl_methods[] = {
      {"set", guarded<pl_set>, "load:set{...} or load:set(fx, fy)\nA new force, as m:point_load takes it.",
       kForceOptions},
      {"force", guarded<pl_force>, "load:force() → fx, fy applied in the last (or next) step"},
      {"block", guarded<pl_block>, "load:block() → the Block the load acts on"},
      {}};
  static const luaL_Reg pl_meta[] = {{"__tostring", pl_tostring}, {nullptr, nullptr}};
  define_type(L, kPointLoadType, pl_methods, pl_meta);
  static const Method pr_methods[] = {
      {"set", guarded<pr_set>, "pressure:set(p): a number, {{t, p}, ...} or function(t)"},
      {"value", guarded<pr_value>, "pressure:value() → the pressure applied in the last (or next) step (Pa)"},
      {"edges", guarded<pr_edges>, "pressure:edges() → the EdgeSet it acts on"},
      {}};
  static const luaL_Reg pr_meta[] = {{"__tostring", pr_tostring}, {nullptr, nullptr}};
  define_type(L, kPressureType, pr_methods, pr_meta);
}

}  // namespace dda::script
