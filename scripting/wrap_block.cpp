// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// dda.Block and dda.BlockSet, and the model's block calls: m:add_block{...},
// m:block(id), m:block_at(x, y), m:blocks{...}, m:block_count().
#include <algorithm>
#include <cmath>

#include "geometry/polygon.hpp"
#include "wrap.hpp"

namespace dda::script {

namespace {

// ---- model calls ----------------------------------------------------------------------------------

constexpr Name kAddBlockOptions[] = {
    {"polygon", "the outline {{x, y}, ...} (either orientation), or give the points inline: m:add_block{{x, y}, ...}",
     "the points inline"},
    {"rock", "its RockMaterial", "the first rock material"},
    {"joint", "the JointMaterial of every edge", "the default joint"},
    {"joints", "one JointMaterial per edge (edge k from point k to k + 1)", "the default joint"}};

// m:add_block{{x, y}, ... | polygon = {...}, rock = r, joint = j | joints = {j1, j2, ...}} → Block
int m_add_block(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:add_block");
  check_not_busy(m, "m:add_block");
  const Options o(L, 2, "m:add_block", kAddBlockOptions, true);
  if ((o.array_size() > 0) == o.has("polygon"))
    fail("m:add_block: give the outline once, inline {{x, y}, ...} or as polygon = {...}");
  std::vector<Vec2> pts =
      o.array_size() > 0 ? check_polygon(L, o.index(), "m:add_block", "the outline") : o.polygon("polygon");
  int rock = -1;
  if (o.has("rock")) {
    o.push("rock");
    rock = check_rock(L, -1, &m, "m:add_block", "option 'rock'");
    lua_pop(L, 1);
  } else {
    if (m.world().rock_material_count() == 0)
      fail("m:add_block: no rock material yet: create one with m:rock{...} first, or pass rock = ...");
    rock = 0;
  }
  std::vector<int> joints;
  if (o.has("joint") && o.has("joints"))
    fail("m:add_block: give either 'joint' (every edge) or 'joints' (one per edge)");
  if (o.has("joint")) {
    o.push("joint");
    joints.assign(pts.size(), check_joint(L, -1, &m, "m:add_block", "option 'joint'"));
    lua_pop(L, 1);
  } else if (o.has("joints")) {
    o.push("joints");
    const int t = lua_gettop(L);
    if (lua_type(L, t) != LUA_TTABLE)
      fail("m:add_block: option 'joints' must be a list of joint materials, one per edge");
    if (lua_rawlen(L, t) != pts.size())
      fail("m:add_block: option 'joints' has ", lua_rawlen(L, t), " entries for ", pts.size(), " edges");
    for (std::size_t k = 1; k <= pts.size(); ++k) {
      lua_rawgeti(L, t, static_cast<lua_Integer>(k));
      joints.push_back(check_joint(L, -1, &m, "m:add_block", msg("option 'joints' entry ", k)));
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  const BlockId b = m.add_block(std::move(pts), rock, std::move(joints));
  push_block(L, 1, b);
  return 1;
}

// m:block(id) → Block (ids are the engine's, from 0)
int m_block(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:block");
  const long id = check_integer(L, 2, "m:block", "argument 1 (block id)");
  if (id < 0 || static_cast<std::size_t>(id) >= m.world().block_count())
    fail("m:block: no block ", id, " (the model has ", m.world().block_count(), " blocks, ids from 0)");
  push_block(L, 1, static_cast<BlockId>(id));
  return 1;
}

Vec2 point_args(lua_State* L, int idx, const char* call) {
  if (lua_type(L, idx) == LUA_TTABLE) return check_point(L, idx, call, "argument 1 (point)");
  return Vec2(check_number(L, idx, call, "argument 1 (x)"), check_number(L, idx + 1, call, "argument 2 (y)"));
}

// m:block_at(x, y) or m:block_at{x, y} → Block or nil
int m_block_at(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:block_at");
  const Vec2 p = point_args(L, 2, "m:block_at");
  if (const auto b = m.block_at(p)) {
    push_block(L, 1, *b);
    return 1;
  }
  lua_pushnil(L);
  return 1;
}

int m_block_count(lua_State* L) {
  lua_pushinteger(L, static_cast<lua_Integer>(check_model(L, 1, "m:block_count").world().block_count()));
  return 1;
}

constexpr Name kBlocksOptions[] = {{"in_box", "{x1, y1, x2, y2}: blocks whose centroid lies in the box", "any"},
                                   {"containing", "{x, y}: the block that contains the point", "any"},
                                   {"rock", "blocks of this RockMaterial", "any"},
                                   {"where", "function(block) → boolean: blocks for which it returns true", "any"}};

// m:blocks{in_box = {x1, y1, x2, y2}, containing = {x, y}, rock = r, where = f} → BlockSet
// (no table: every block). Criteria combine with "and".
int m_blocks(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:blocks");
  const World& w = m.world();
  std::optional<std::array<double, 4>> box;
  std::optional<Vec2> containing;
  int rock = -1;
  int where = 0;
  if (!lua_isnoneornil(L, 2)) {
    const Options o(L, 2, "m:blocks", kBlocksOptions);
    if (o.has("in_box")) box = o.quad("in_box");
    if (o.has("containing")) containing = o.point("containing");
    if (o.has("rock")) {
      o.push("rock");
      rock = check_rock(L, -1, &m, "m:blocks", "option 'rock'");
      lua_pop(L, 1);
    }
    if (o.has("where")) {
      if (o.push("where") != LUA_TFUNCTION) fail("m:blocks: option 'where' must be a function(block) → boolean");
      where = lua_gettop(L);
    }
  }
  std::vector<BlockId> out;
  const auto count = static_cast<BlockId>(w.block_count());
  for (BlockId b = 0; b < count; ++b) {
    if (rock >= 0 && w.block_material(b) != rock) continue;
    if (box) {
      const Vec2 c = w.block_centroid(b);
      const auto& q = *box;
      if (c.x() < std::min(q[0], q[2]) || c.x() > std::max(q[0], q[2]) || c.y() < std::min(q[1], q[3]) ||
          c.y() > std::max(q[1], q[3]))
        continue;
    }
    if (containing && !point_in_polygon(w.block_vertices(b), *containing)) continue;
    if (where) {
      lua_pushvalue(L, where);
      push_block(L, 1, b);
      pcall(L, 1, 1);
      const bool keep = lua_toboolean(L, -1);
      lua_pop(L, 1);
      if (!keep) continue;
    }
    out.push_back(b);
  }
  push_blockset(L, 1, out);
  return 1;
}

// ---- dda.Block ----------------------------------------------------------------------------------

struct Self {
  ScriptModel* model;
  BlockId id;
};
Self self_block(lua_State* L, const char* call) {
  Handle* h = check_handle(L, 1, kBlockType, call, "self");
  return {h->model, check_block(L, 1, h->model, call, "self")};
}

int b_id(lua_State* L) {
  lua_pushinteger(L, self_block(L, "b:id").id);
  return 1;
}
int b_centroid(lua_State* L) {
  const Self s = self_block(L, "b:centroid");
  const Vec2 c = s.model->world().block_centroid(s.id);
  lua_pushnumber(L, c.x());
  lua_pushnumber(L, c.y());
  return 2;
}
int b_area(lua_State* L) {
  const Self s = self_block(L, "b:area");
  lua_pushnumber(L, s.model->world().block_area(s.id));
  return 1;
}
int b_mass(lua_State* L) {
  const Self s = self_block(L, "b:mass");
  lua_pushnumber(L, s.model->world().block_mass(s.id));
  return 1;
}
int b_rock(lua_State* L) {
  const Self s = self_block(L, "b:rock");
  push_model_of(L, 1);
  push_rock(L, -1, s.model->world().block_material(s.id));
  return 1;
}
int b_vertices(lua_State* L) {
  const Self s = self_block(L, "b:vertices");
  const auto v = s.model->world().block_vertices(s.id);
  lua_createtable(L, static_cast<int>(v.size()), 0);
  for (std::size_t k = 0; k < v.size(); ++k) {
    push_point(L, v[k]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
  return 1;
}
int b_edges(lua_State* L) {
  const Self s = self_block(L, "b:edges");
  std::vector<EdgeRef> e;
  for (int k = 0; k < s.model->edge_count(s.id); ++k) e.push_back({s.id, k});
  push_model_of(L, 1);
  push_edgeset(L, -1, e);
  return 1;
}
int b_stress(lua_State* L) {
  const Self s = self_block(L, "b:stress");
  const Vec3 st = s.model->world().block_stress(s.id);
  for (int k = 0; k < 3; ++k) lua_pushnumber(L, st[k]);
  return 3;
}
// b:velocity() → vx, vy, ω of the centroid (rad/s)
int b_velocity(lua_State* L) {
  const Self s = self_block(L, "b:velocity");
  const Vec6 v = s.model->world().block_velocity(s.id);
  for (int k = 0; k < 3; ++k) lua_pushnumber(L, v[k]);
  return 3;
}
int b_velocity_at(lua_State* L) {
  const Self s = self_block(L, "b:velocity_at");
  const Vec2 p = point_args(L, 2, "b:velocity_at");
  const Vec2 v = s.model->world().velocity_at(s.id, p);
  lua_pushnumber(L, v.x());
  lua_pushnumber(L, v.y());
  return 2;
}
int b_displacement(lua_State* L) {
  const Self s = self_block(L, "b:displacement");
  const Vec2 d = s.model->world().block_displacement(s.id);
  lua_pushnumber(L, d.x());
  lua_pushnumber(L, d.y());
  return 2;
}
int b_contains(lua_State* L) {
  const Self s = self_block(L, "b:contains");
  lua_pushboolean(L, point_in_polygon(s.model->world().block_vertices(s.id), point_args(L, 2, "b:contains")));
  return 1;
}

void set_velocity(ScriptModel& m, std::span<const BlockId> blocks, lua_State* L, const char* call) {
  check_not_busy(m, call);
  Vec6 v = Vec6::Zero();
  v[0] = check_number(L, 2, call, "argument 1 (vx)");
  v[1] = check_number(L, 3, call, "argument 2 (vy)");
  v[2] = opt_number(L, 4, 0, call, "argument 3 (angular velocity, rad/s)");
  for (BlockId b : blocks) m.world().set_block_velocity(b, v);
}
void set_stress(ScriptModel& m, std::span<const BlockId> blocks, lua_State* L, const char* call) {
  check_not_busy(m, call);
  const Vec3 s(check_number(L, 2, call, "argument 1 (sxx)"), check_number(L, 3, call, "argument 2 (syy)"),
               opt_number(L, 4, 0, call, "argument 3 (txy)"));
  for (BlockId b : blocks) m.world().set_block_stress(b, s);
}
// Fixed points at (x, y), or at every vertex of each block.
int fix_blocks(ScriptModel& m, std::span<const BlockId> blocks, lua_State* L, const char* call) {
  check_not_busy(m, call);
  int n = 0;
  if (!lua_isnoneornil(L, 2)) {
    const Vec2 p = point_args(L, 2, call);
    for (BlockId b : blocks) m.add_fixed_point(b, p), ++n;
  } else {
    for (BlockId b : blocks)
      for (const Vec2& v : std::vector<Vec2>(m.world().block_vertices(b).begin(), m.world().block_vertices(b).end()))
        m.add_fixed_point(b, v), ++n;
  }
  return n;
}

int b_set_velocity(lua_State* L) {
  const Self s = self_block(L, "b:set_velocity");
  set_velocity(*s.model, std::span<const BlockId>(&s.id, 1), L, "b:set_velocity");
  return 0;
}
int b_set_stress(lua_State* L) {
  const Self s = self_block(L, "b:set_stress");
  set_stress(*s.model, std::span<const BlockId>(&s.id, 1), L, "b:set_stress");
  return 0;
}
// b:fix() (every vertex) or b:fix(x, y) → number of fixed points added
int b_fix(lua_State* L) {
  const Self s = self_block(L, "b:fix");
  lua_pushinteger(L, fix_blocks(*s.model, std::span<const BlockId>(&s.id, 1), L, "b:fix"));
  return 1;
}

int block_eq(lua_State* L) {
  auto* a = static_cast<Handle*>(lua_touserdata(L, 1));
  auto* b = static_cast<Handle*>(lua_touserdata(L, 2));
  lua_pushboolean(L, a && b && a->model == b->model && a->id == b->id);
  return 1;
}
int block_tostring(lua_State* L) {
  auto* h = static_cast<Handle*>(luaL_checkudata(L, 1, kBlockType));
  lua_pushfstring(L, "dda.Block %d", static_cast<int>(h->id));
  return 1;
}

// ---- dda.BlockSet ----------------------------------------------------------------------------------

struct SetSelf {
  ScriptModel* model;
  std::vector<BlockId> blocks;
};
SetSelf self_set(lua_State* L, const char* call) {
  Handle* h = check_handle(L, 1, kBlockSetType, call, "self");
  return {h->model, check_blockset(L, 1, h->model, call, "self")};
}

int bs_index(lua_State* L) {
  if (!lua_isinteger(L, 2)) return 0;
  Handle* h = check_handle(L, 1, kBlockSetType, "blocks[i]", "self");
  const lua_Integer i = lua_tointeger(L, 2);
  if (i < 1 || i > h->count) {
    lua_pushnil(L);
    return 1;
  }
  const BlockId b = set_blocks(h)[i - 1];
  if (static_cast<std::size_t>(b) >= h->model->world().block_count())
    fail("blocks[", i, "]: attempt to use a removed/invalid block (id ", b, ")");
  push_model_of(L, 1);
  push_block(L, -1, b);
  return 1;
}
int bs_len(lua_State* L) {
  auto* h = static_cast<Handle*>(luaL_checkudata(L, 1, kBlockSetType));
  lua_pushinteger(L, h->count);
  return 1;
}
int bs_count(lua_State* L) {
  lua_pushinteger(L, static_cast<lua_Integer>(self_set(L, "blocks:count").blocks.size()));
  return 1;
}
int bs_ids(lua_State* L) {
  const SetSelf s = self_set(L, "blocks:ids");
  lua_createtable(L, static_cast<int>(s.blocks.size()), 0);
  for (std::size_t i = 0; i < s.blocks.size(); ++i) {
    lua_pushinteger(L, s.blocks[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}
int bs_area(lua_State* L) {
  const SetSelf s = self_set(L, "blocks:area");
  double a = 0;
  for (BlockId b : s.blocks) a += s.model->world().block_area(b);
  lua_pushnumber(L, a);
  return 1;
}
int bs_edges(lua_State* L) {
  const SetSelf s = self_set(L, "blocks:edges");
  std::vector<EdgeRef> e;
  for (BlockId b : s.blocks)
    for (int k = 0; k < s.model->edge_count(b); ++k) e.push_back({b, k});
  push_model_of(L, 1);
  push_edgeset(L, -1, e);
  return 1;
}
int bs_set_velocity(lua_State* L) {
  SetSelf s = self_set(L, "blocks:set_velocity");
  set_velocity(*s.model, s.blocks, L, "blocks:set_velocity");
  return 0;
}
int bs_set_stress(lua_State* L) {
  SetSelf s = self_set(L, "blocks:set_stress");
  set_stress(*s.model, s.blocks, L, "blocks:set_stress");
  return 0;
}
int bs_fix(lua_State* L) {
  SetSelf s = self_set(L, "blocks:fix");
  lua_pushinteger(L, fix_blocks(*s.model, s.blocks, L, "blocks:fix"));
  return 1;
}
// blocks:filter(function(b) return ... end) → BlockSet
int bs_filter(lua_State* L) {
  const SetSelf s = self_set(L, "blocks:filter");
  if (lua_type(L, 2) != LUA_TFUNCTION)
    fail("blocks:filter: argument 1 must be a function(block) → boolean, got ", type_of(L, 2));
  push_model_of(L, 1);
  const int model_idx = lua_gettop(L);
  std::vector<BlockId> out;
  for (BlockId b : s.blocks) {
    lua_pushvalue(L, 2);
    push_block(L, model_idx, b);
    pcall(L, 1, 1);
    const bool keep = lua_toboolean(L, -1);
    lua_pop(L, 1);
    if (keep) out.push_back(b);
  }
  push_blockset(L, model_idx, out);
  return 1;
}
int bs_tostring(lua_State* L) {
  auto* h = static_cast<Handle*>(luaL_checkudata(L, 1, kBlockSetType));
  lua_pushfstring(L, "dda.BlockSet (%d blocks)", static_cast<int>(h->count));
  return 1;
}

}  // namespace

void register_block(lua_State* L) {
  static const Method model_methods[] = {
      {"add_block", guarded<m_add_block>,
       "m:add_block{...} → Block\nA block from its outline, given inline (m:add_block{{0, 0}, {1, 0}, {1, 1}}) "
       "or as `polygon`. A rock whose material has a mesh_size is meshed (its first element is returned).",
       kAddBlockOptions},
      {"block", guarded<m_block>, "m:block(id) → Block (ids are the engine's, from 0)"},
      {"block_at", guarded<m_block_at>, "m:block_at(x, y) or m:block_at{x, y} → Block or nil"},
      {"blocks", guarded<m_blocks>,
       "m:blocks{...} → BlockSet\nThe blocks that meet every criterion given (m:blocks() every block).",
       kBlocksOptions},
      {"block_count", guarded<m_block_count>, "m:block_count() → the number of blocks"},
      {}};
  add_model_methods(L, model_methods, "Blocks");

  static const Method block_methods[] = {
      {"id", guarded<b_id>, "b:id() → the block's engine id (from 0)"},
      {"centroid", guarded<b_centroid>, "b:centroid() → x, y of the centroid now"},
      {"area", guarded<b_area>, "b:area() → area (m²)"},
      {"mass", guarded<b_mass>, "b:mass() → mass (kg per unit thickness)"},
      {"rock", guarded<b_rock>, "b:rock() → its RockMaterial"},
      {"vertices", guarded<b_vertices>, "b:vertices() → {{x, y}, ...}: the outline now, counter-clockwise"},
      {"edges", guarded<b_edges>, "b:edges() → EdgeSet of its edges"},
      {"stress", guarded<b_stress>,
       "b:stress() → sxx, syy, txy (Pa, tension positive; constant over a first-order block)"},
      {"velocity", guarded<b_velocity>, "b:velocity() → vx, vy, ω of the centroid (rad/s)"},
      {"velocity_at", guarded<b_velocity_at>, "b:velocity_at(x, y) → vx, vy of the block's material at a point (m/s)"},
      {"displacement", guarded<b_displacement>,
       "b:displacement() → ux, uy of the centroid since the start, or since m:settle (m)"},
      {"contains", guarded<b_contains>, "b:contains(x, y) → whether the point lies inside the block"},
      {"set_velocity", guarded<b_set_velocity>,
       "b:set_velocity(vx, vy [, ω]): the initial (or current) velocity (m/s, rad/s)"},
      {"set_stress", guarded<b_set_stress>,
       "b:set_stress(sxx, syy [, txy]): the initial stress (Pa, tension positive)"},
      {"fix", guarded<b_fix>, "b:fix() (every vertex) or b:fix(x, y) → number of fixed points added"},
      {}};
  static const luaL_Reg block_meta[] = {{"__eq", block_eq}, {"__tostring", block_tostring}, {nullptr, nullptr}};
  define_type(L, kBlockType, block_methods, block_meta);

  static const Method set_methods[] = {
      {"count", guarded<bs_count>, "blocks:count() → the number of blocks in the set (also #blocks)"},
      {"ids", guarded<bs_ids>, "blocks:ids() → {id, ...}: their engine ids"},
      {"area", guarded<bs_area>, "blocks:area() → their total area (m²)"},
      {"edges", guarded<bs_edges>, "blocks:edges() → EdgeSet of every edge of the set's blocks"},
      {"set_velocity", guarded<bs_set_velocity>,
       "blocks:set_velocity(vx, vy [, ω]): the same velocity for every block of the set"},
      {"set_stress", guarded<bs_set_stress>,
       "blocks:set_stress(sxx, syy [, txy]): the same initial stress for every block (Pa)"},
      {"fix", guarded<bs_fix>, "blocks:fix([x, y]) → number of fixed points added (at (x, y), or at every vertex)"},
      {"filter", guarded<bs_filter>, "blocks:filter(function(b) return ... end) → BlockSet"},
      {}};
  static const luaL_Reg set_meta[] = {{"__len", bs_len}, {"__tostring", bs_tostring}, {nullptr, nullptr}};
  define_type(L, kBlockSetType, set_methods, set_meta, guarded<bs_index>);
}

}  // namespace dda::script
