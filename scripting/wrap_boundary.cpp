// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Boundaries and prescribed displacements on edges and points (the paper's
// VBC, SBC and DHI, as implemented by the engine):
//   edges:viscous_boundary{rock = r, vx = h, vy = h} → dda.Boundary
//   edges:spring_boundary{p = ..., per_length = true} → dda.Boundary
//   edges:free_field{base = boundary}             → dda.Boundary
//   edges:target{displacement = h | velocity = h | acceleration = h, direction = {dx, dy}} → dda.Target
//   m:target{at = {x, y}, block = b, direction = {dx, dy}, displacement = h | velocity = h | acceleration = h} →
//   dda.Target
#include <map>

#include "wrap.hpp"

namespace dda::script {

namespace {

constexpr const char* kBoundaryType = "dda.Boundary";
constexpr const char* kTargetType = "dda.Target";

struct EdgesSelf {
  ScriptModel* model;
  std::vector<EdgeRef> edges;
};
EdgesSelf self_edges(lua_State* L, const char* call) {
  Handle* h = check_handle(L, 1, kEdgeSetType, call, "self");
  EdgesSelf s{h->model, check_edgeset(L, 1, h->model, call, "self")};
  check_not_busy(*s.model, call);
  if (s.edges.empty()) fail(call, ": the edge set is empty (check the selection that made it)");
  return s;
}

// A history the engine evaluates itself (a number or a table, not a function).
History engine_history(const Options& o, const char* key) {
  lua_State* L = o.state();
  o.push(key);
  if (lua_type(L, -1) == LUA_TFUNCTION)
    fail(o.call(), ": option '", key,
         "' must be a number or a table of {t, v} pairs (the engine evaluates it "
         "at each step's end), not a function");
  const TimeInput input = TimeInput::parse(L, -1, o.call(), msg("option '", key, "'"));
  lua_pop(L, 1);
  return input.engine_history();
}

constexpr Name kViscousOptions[] = {
    {"rock", "a RockMaterial: ρ, C_P and C_S of the medium beyond (the half-space below a compliant base)",
     "each edge's own block"},
    {"vx", "the incident wave's x particle velocity (m/s), a number or {{t, v}, ...}: a compliant base", "none"},
    {"vy", "its y particle velocity (m/s), as vx", "none"}};
constexpr Name kFreeFieldOptions[] = {
    {"base", "the compliant base whose incident wave drives the column (an edges:viscous_boundary{vx = ...})",
     nullptr}};
constexpr Name kSpringOptions[] = {
    {"p", "the spring's stiffness: N/m per m of edge (per_length), else N/m", nullptr},
    {"per_length", "true: Eq. 22, a spring p·l at each end of each edge; false: Eq. 21, p alone", "true"}};
// What moves a target: one of these, each a history (a number, {{t, v}, ...}
// or, for a displacement, a function of t).
constexpr Name kTargetMotion[] = {
    {"displacement",
     "{ux, uy} (m), a fixed vector; or a history along `direction` (a number, {{t, u}, ...} or a function(t))", "—"},
    {"velocity", "a history (m/s, a number or {{t, v}, ...}) along `direction`, integrated to displacement", "—"},
    {"acceleration", "a history (m/s², a number or {{t, a}, ...}), integrated twice from rest: a shaken base", "—"}};
const std::vector<Name> kEdgesTargetOptions = [] {
  std::vector<Name> n(std::begin(kTargetMotion), std::end(kTargetMotion));
  n.push_back({"direction", "{dx, dy}: the direction of the motion", "each point's inward edge normal"});
  return n;
}();
const std::vector<Name> kTargetOptions = [] {
  std::vector<Name> n = {{"at", "{x, y}: the material point moved", nullptr},
                         {"block", "the Block it belongs to", "the block containing `at`"},
                         {"direction", "{dx, dy}: the direction of the motion", "none: give displacement = {ux, uy}"}};
  n.insert(n.end(), std::begin(kTargetMotion), std::end(kTargetMotion));
  return n;
}();

// edges:viscous_boundary{rock = r, vx = h, vy = h} → Boundary (all options optional)
int es_viscous(lua_State* L) {
  EdgesSelf s = self_edges(L, "edges:viscous_boundary");
  if (lua_isnoneornil(L, 2)) {  // edges:viscous_boundary(): no options
    lua_settop(L, 1);
    lua_newtable(L);
  }
  const Options o(L, 2, "edges:viscous_boundary", kViscousOptions);
  int medium = -1;
  if (o.has("rock")) {
    o.push("rock");
    medium = check_rock(L, -1, s.model, o.call(), "option 'rock'");
    lua_pop(L, 1);
  }
  const int id = s.model->world().add_viscous_boundary(s.edges, medium);
  if (o.has("vx") || o.has("vy"))
    s.model->world().set_incident_velocity(id, o.has("vx") ? engine_history(o, "vx") : History(),
                                           o.has("vy") ? engine_history(o, "vy") : History());
  push_model_of(L, 1);
  push_handle(L, -1, kBoundaryType, id);
  return 1;
}

// edges:free_field{base = boundary} → Boundary: the edges (one vertical side)
// coupled to a 1-D free-field column driven by the compliant base's wave.
int es_free_field(lua_State* L) {
  EdgesSelf s = self_edges(L, "edges:free_field");
  const Options o(L, 2, "edges:free_field", kFreeFieldOptions);
  if (!o.has("base")) fail("edges:free_field: option 'base' (the compliant base, a dda.Boundary) is required");
  o.push("base");
  Handle* base = check_handle(L, -1, kBoundaryType, "edges:free_field", "option 'base'");
  check_same_model(base, s.model, "edges:free_field", "option 'base'");
  const int base_id = base->id;
  lua_pop(L, 1);
  const int id = s.model->world().add_free_field(s.edges, base_id);
  push_model_of(L, 1);
  push_handle(L, -1, kBoundaryType, id);
  return 1;
}

// edges:spring_boundary{p = stiffness, per_length = true} → Boundary
// (per_length: Eq. 22, spring p·l at each end; false: Eq. 21, p alone)
int es_spring(lua_State* L) {
  EdgesSelf s = self_edges(L, "edges:spring_boundary");
  const Options o(L, 2, "edges:spring_boundary", kSpringOptions);
  const double p = o.positive("p");
  const bool per_length = o.boolean("per_length", true);
  const int id = s.model->world().add_spring_boundary(s.edges, p, per_length);
  push_model_of(L, 1);
  push_handle(L, -1, kBoundaryType, id);
  return 1;
}

// The input of a target: displacement = {ux, uy} (a fixed vector) or a
// history (number, {{t, u}, ...}, function of t) along the direction; or
// velocity = a history (number or table; the engine integrates it); or
// acceleration = a history (integrated twice from rest: a shaken base).
ScriptTarget read_target(const Options& o, bool directed) {
  lua_State* L = o.state();
  ScriptTarget t;
  const int which = one_of(o, {"displacement", "velocity", "acceleration"});
  if (which > 0) {
    const char* key = which == 1 ? "velocity" : "acceleration";
    t.mode = which == 1 ? ScriptTarget::Mode::Velocity : ScriptTarget::Mode::Acceleration;
    o.push(key);
    if (lua_type(L, -1) == LUA_TFUNCTION)
      fail(o.call(), ": option '", key, "' must be a number or a table of {t, v} pairs (the engine integrates it); ",
           "give a function of t as displacement instead");
    t.input = TimeInput::parse(L, -1, o.call(), msg("option '", key, "'"));
    lua_pop(L, 1);
  } else {
    o.push("displacement");
    const int idx = lua_gettop(L);
    bool vector = false;
    if (lua_type(L, idx) == LUA_TTABLE && lua_rawlen(L, idx) == 2) {
      lua_rawgeti(L, idx, 1);
      vector = lua_type(L, -1) == LUA_TNUMBER;
      lua_pop(L, 1);
    }
    if (vector) {
      t.mode = ScriptTarget::Mode::Vector;
      t.vector = check_point(L, idx, o.call(), "option 'displacement' {ux, uy}");
    } else {
      t.mode = ScriptTarget::Mode::Displacement;
      t.input = TimeInput::parse(L, idx, o.call(), "option 'displacement'");
    }
    lua_pop(L, 1);
  }
  if (t.mode != ScriptTarget::Mode::Vector && !directed)
    fail(o.call(), ": a displacement or velocity history needs a direction = {dx, dy}");
  return t;
}

// edges:target{displacement = h | velocity = h | acceleration = h, direction = {dx, dy}} → Target.
// A target at each end point of each edge (once per block vertex); without a
// direction each point moves along the edge normal into its block (the mean
// of its edges' normals where two edges of the set meet).
int es_target(lua_State* L) {
  EdgesSelf s = self_edges(L, "edges:target");
  const Options o(L, 2, "edges:target", kEdgesTargetOptions);
  std::optional<Vec2> direction;
  if (o.has("direction")) {
    direction = o.point("direction");
    if (direction->norm() == 0) fail("edges:target: option 'direction' must not be zero");
  }
  ScriptTarget target = read_target(o, true);
  const int id = s.model->add_edge_targets(s.edges, direction ? *direction : Vec2(Vec2::Zero()), std::move(target), L);
  push_model_of(L, 1);
  push_handle(L, -1, kTargetType, id);
  return 1;
}

// m:target{at = {x, y}, block = b, direction = {dx, dy}, displacement = h | velocity = h | acceleration = h} → Target
int m_target(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:target");
  check_not_busy(m, "m:target");
  const Options o(L, 2, "m:target", kTargetOptions);
  const Vec2 at = o.point("at");
  BlockId b;
  if (o.has("block")) {
    o.push("block");
    b = check_block(L, -1, &m, "m:target", "option 'block'");
    lua_pop(L, 1);
  } else {
    const auto found = m.block_at(at);
    if (!found) fail("m:target: no block at (", at.x(), ", ", at.y(), "); give block = ... or a point inside a block");
    b = *found;
  }
  std::vector<Vec2> directions;
  if (o.has("direction")) {
    const Vec2 d = o.point("direction");
    if (d.norm() == 0) fail("m:target: option 'direction' must not be zero");
    directions.push_back(d.normalized());
  }
  ScriptTarget target = read_target(o, !directions.empty());
  if (target.mode == ScriptTarget::Mode::Vector) directions.clear();
  const int id = m.add_target({{b, at}}, directions, std::move(target), L);
  push_handle(L, 1, kTargetType, id);
  return 1;
}

// ---- dda.Boundary --------------------------------------------------------------------

Handle* self_boundary(lua_State* L, const char* call) { return check_handle(L, 1, kBoundaryType, call, "self"); }

// boundary:force() → fx, fy: the total force its points exerted in the last step (N per unit thickness)
int bd_force(lua_State* L) {
  Handle* h = self_boundary(L, "boundary:force");
  const Vec2 f = h->model->world().boundary_force(h->id);
  lua_pushnumber(L, f.x());
  lua_pushnumber(L, f.y());
  return 2;
}

// boundary:free_field_velocity(y) → vx, vy of a free-field boundary's column at the node nearest height y
int bd_free_field_velocity(lua_State* L) {
  Handle* h = self_boundary(L, "boundary:free_field_velocity");
  const Vec2 v = h->model->world().free_field_velocity(
      h->id, check_number(L, 2, "boundary:free_field_velocity", "argument 1 (y)"));
  lua_pushnumber(L, v.x());
  lua_pushnumber(L, v.y());
  return 2;
}

// boundary:point_forces() → {{fx, fy}, ...}, two points per edge in edge order
int bd_point_forces(lua_State* L) {
  Handle* h = self_boundary(L, "boundary:point_forces");
  const auto forces = h->model->world().boundary_point_forces(h->id);
  lua_createtable(L, static_cast<int>(forces.size()), 0);
  for (std::size_t i = 0; i < forces.size(); ++i) {
    push_point(L, forces[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}

int bd_tostring(lua_State* L) {
  auto* h = static_cast<Handle*>(luaL_checkudata(L, 1, kBoundaryType));
  lua_pushfstring(L, "dda.Boundary %d", static_cast<int>(h->id + 1));
  return 1;
}

// ---- dda.Target -----------------------------------------------------------------------------

Handle* self_target(lua_State* L, const char* call) {
  Handle* h = check_handle(L, 1, kTargetType, call, "self");
  if (h->id < 0 || h->id >= h->model->target_count()) fail(call, ": attempt to use an invalid target");
  return h;
}

// target:set{displacement = ... | velocity = ... | acceleration = ...}
int tg_set(lua_State* L) {
  Handle* h = self_target(L, "target:set");
  check_not_busy(*h->model, "target:set");
  const Options o(L, 2, "target:set", kTargetMotion);
  ScriptTarget& old = h->model->target(h->id);
  ScriptTarget input = read_target(o, old.mode != ScriptTarget::Mode::Vector);
  if (old.mode == ScriptTarget::Mode::Vector && input.mode != ScriptTarget::Mode::Vector)
    fail("target:set: this target has no direction: give displacement = {ux, uy}");
  if (old.mode != ScriptTarget::Mode::Vector && input.mode == ScriptTarget::Mode::Vector)
    fail("target:set: this target moves along a direction: give a displacement or velocity history");
  h->model->set_target(h->id, std::move(input), L);
  return 0;
}

// target:displacement([i]) → ux, uy of point i (default: the mean over its points)
int tg_displacement(lua_State* L) {
  Handle* h = self_target(L, "target:displacement");
  const ScriptTarget& t = h->model->target(h->id);
  Vec2 u = Vec2::Zero();
  if (!lua_isnoneornil(L, 2)) {
    const long i = check_integer(L, 2, "target:displacement", "argument 1 (point)");
    if (i < 1 || i > static_cast<long>(t.world_ids.size()))
      fail("target:displacement: no point ", i, " (the target has ", t.world_ids.size(), ")");
    u = h->model->world().target_point_displacement(t.world_ids[i - 1]);
  } else {
    for (int id : t.world_ids) u += h->model->world().target_point_displacement(id);
    u /= static_cast<double>(t.world_ids.size());
  }
  lua_pushnumber(L, u.x());
  lua_pushnumber(L, u.y());
  return 2;
}

// target:value([i]) → tx, ty: the target displacement applied in the last step at point i (default 1)
int tg_value(lua_State* L) {
  Handle* h = self_target(L, "target:value");
  const ScriptTarget& t = h->model->target(h->id);
  const long i = lua_isnoneornil(L, 2) ? 1 : check_integer(L, 2, "target:value", "argument 1 (point)");
  if (i < 1 || i > static_cast<long>(t.world_ids.size()))
    fail("target:value: no point ", i, " (the target has ", t.world_ids.size(), ")");
  const Vec2 v = h->model->world().target_value(t.world_ids[i - 1]);
  lua_pushnumber(L, v.x());
  lua_pushnumber(L, v.y());
  return 2;
}

int tg_count(lua_State* L) {
  Handle* h = self_target(L, "target:count");
  lua_pushinteger(L, static_cast<lua_Integer>(h->model->target(h->id).world_ids.size()));
  return 1;
}

int tg_tostring(lua_State* L) {
  auto* h = static_cast<Handle*>(luaL_checkudata(L, 1, kTargetType));
  lua_pushfstring(L, "dda.Target %d", static_cast<int>(h->id + 1));
  return 1;
}

}  // namespace

void register_boundaries(lua_State* L) {
  static const Method edge_methods[] = {
      {"viscous_boundary", guarded<es_viscous>,
       "edges:viscous_boundary{...} → Boundary\nDashpots ρC_P (normal) and ρC_S (along the edge) that absorb "
       "waves leaving the model (Eqs. 6-12). With vx, vy it is a compliant base: the incident wave comes in as the "
       "traction 2ρC·v_in (vertically incident S: vx on a horizontal base; P: vy). docs/seismic.md.",
       kViscousOptions},
      {"free_field", guarded<es_free_field>,
       "edges:free_field{...} → Boundary\nA free-field side: the edges (one vertical side of the model, all facing "
       "the same way) are coupled to a 1-D column beside them, driven by the incident wave of `base`, through "
       "dashpots ρC_P, ρC_S against the column's velocity and the column's stresses. Once per side. "
       "docs/seismic.md.",
       kFreeFieldOptions},
      {"spring_boundary", guarded<es_spring>,
       "edges:spring_boundary{...} → Boundary\nSprings at the edges' end points that resist each step's "
       "displacement (the paper's SBC).",
       kSpringOptions},
      {"target", guarded<es_target>,
       "edges:target{...} → Target\nA prescribed motion at each end point of each edge (once per block vertex); "
       "without a direction each point moves along the edge normal into its block (the mean of its edges' normals "
       "where two edges of the set meet).",
       kEdgesTargetOptions},
      {}};
  add_methods(L, kEdgeSetType, edge_methods);
  static const Method model_methods[] = {
      {"target", guarded<m_target>,
       "m:target{...} → Target\nA prescribed motion of a material point (the paper's DHI: a stiff spring to the "
       "moving target).",
       kTargetOptions},
      {}};
  add_model_methods(L, model_methods, "Prescribed motion");
  static const Method bd_methods[] = {
      {"force", guarded<bd_force>,
       "boundary:force() → fx, fy: the total force its points exerted in the last step (N per unit thickness)"},
      {"point_forces", guarded<bd_point_forces>,
       "boundary:point_forces() → {{fx, fy}, ...}, two points per edge in edge order"},
      {"free_field_velocity", guarded<bd_free_field_velocity>,
       "boundary:free_field_velocity(y) → vx, vy: a free-field boundary's column at the node nearest height y "
       "(after the last step)"},
      {}};
  static const luaL_Reg bd_meta[] = {{"__tostring", bd_tostring}, {nullptr, nullptr}};
  define_type(L, kBoundaryType, bd_methods, bd_meta);
  static const Method tg_methods[] = {
      {"set", guarded<tg_set>, "target:set{...}\nA new motion, as the target was made with.", kTargetMotion},
      {"displacement", guarded<tg_displacement>,
       "target:displacement([i]) → ux, uy of point i (default: the mean over its points)"},
      {"value", guarded<tg_value>,
       "target:value([i]) → tx, ty: the target displacement applied in the last step at point i (default 1)"},
      {"count", guarded<tg_count>, "target:count() → the number of target points"},
      {}};
  static const luaL_Reg tg_meta[] = {{"__tostring", tg_tostring}, {nullptr, nullptr}};
  define_type(L, kTargetType, tg_methods, tg_meta);
}

}  // namespace dda::script
