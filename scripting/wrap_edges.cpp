// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// dda.EdgeSet: m:edges{...} selections, and what can be done with a set of
// edges (fixed points at their ends, a pressure on them).
#include <algorithm>
#include <set>

#include "wrap.hpp"

namespace dda::script {

namespace {

const char* kind_name(EdgeKind k) {
  switch (k) {
    case EdgeKind::Joint:
      return "joint";
    case EdgeKind::Domain:
      return "domain";
    case EdgeKind::Hole:
      return "hole";
    case EdgeKind::Free:
      return "free";
  }
  return "?";
}

constexpr Name kEdgesOptions[] = {
    {"on_segment", "{x1, y1, x2, y2}: edges lying on that segment (both ends within `tol` of it)", "any"},
    {"in_box", "{x1, y1, x2, y2}: edges inside the box", "any"},
    {"boundary", "`\"domain\"` (the domain's outline), `\"hole\"` (holes' outlines) or `\"any\"` (either)", "any edge"},
    {"hole", "edges of this hole (a Hole, or its number from 1)", "any"},
    {"joint", "edges of this JointMaterial", "any"},
    {"block", "edges of this Block", "any"},
    {"tol", "distance (m) within which a point counts as on the segment or in the box", "1e-7 × the model's size"}};

// m:edges{on_segment = {x1, y1, x2, y2}, in_box = {x1, y1, x2, y2},
//         boundary = "domain" | "hole" | "any", hole = h, joint = j, block = b, tol = d} → EdgeSet
int m_edges(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:edges");
  EdgeQuery q;
  if (!lua_isnoneornil(L, 2)) {
    const Options o(L, 2, "m:edges", kEdgesOptions);
    if (o.has("on_segment")) q.on_segment = o.quad("on_segment");
    if (o.has("in_box")) q.in_box = o.quad("in_box");
    if (o.has("boundary")) {
      const std::string b = o.string("boundary");
      if (b == "domain")
        q.boundary = EdgeKind::Domain;
      else if (b == "hole")
        q.boundary = EdgeKind::Hole;
      else if (b == "any")
        q.any_boundary = true;
      else
        fail("m:edges: option 'boundary' must be \"domain\", \"hole\" or \"any\", got \"", b, "\"");
    }
    if (o.has("hole")) {
      o.push("hole");
      if (Handle* h = test_handle(L, -1, kHoleType)) {
        check_same_model(h, &m, "m:edges", "option 'hole'");
        q.hole = h->id;
      } else {
        const long n = check_integer(L, -1, "m:edges", "option 'hole' (a hole from m:hole{...} or its number)");
        if (n < 1 || n > m.hole_count()) fail("m:edges: no hole ", n, " (the model has ", m.hole_count(), " holes)");
        q.hole = static_cast<int>(n - 1);
      }
      lua_pop(L, 1);
    }
    if (o.has("joint")) {
      o.push("joint");
      q.joint = check_joint(L, -1, &m, "m:edges", "option 'joint'");
      lua_pop(L, 1);
    }
    if (o.has("block")) {
      o.push("block");
      q.block = check_block(L, -1, &m, "m:edges", "option 'block'");
      lua_pop(L, 1);
    }
    q.tol = o.non_negative("tol", -1);
  }
  push_edgeset(L, 1, select_edges(m, q));
  return 1;
}

struct Self {
  ScriptModel* model;
  std::vector<EdgeRef> edges;
};
Self self_edges(lua_State* L, const char* call) {
  Handle* h = check_handle(L, 1, kEdgeSetType, call, "self");
  return {h->model, check_edgeset(L, 1, h->model, call, "self")};
}

int es_index(lua_State* L) {
  if (!lua_isinteger(L, 2)) return 0;
  Handle* h = check_handle(L, 1, kEdgeSetType, "edges[i]", "self");
  check_same_model(h, nullptr, "edges[i]", "self");
  const lua_Integer i = lua_tointeger(L, 2);
  const std::vector<EdgeRef> edges = edgeset_edges(h);
  if (i < 1 || i > static_cast<lua_Integer>(edges.size())) {
    lua_pushnil(L);
    return 1;
  }
  const EdgeRef e = edges[i - 1];
  if (static_cast<std::size_t>(e.block) >= h->model->world().block_count())
    fail("edges[", i, "]: attempt to use a removed/invalid block (id ", e.block, ")");
  const auto [a, b] = h->model->edge_points(e);
  push_model_of(L, 1);
  lua_createtable(L, 0, 6);
  push_block(L, -2, e.block);
  lua_setfield(L, -2, "block");
  lua_pushinteger(L, e.edge + 1);
  lua_setfield(L, -2, "edge");
  push_point(L, a);
  lua_setfield(L, -2, "from");
  push_point(L, b);
  lua_setfield(L, -2, "to");
  lua_pushnumber(L, (b - a).norm());
  lua_setfield(L, -2, "length");
  lua_pushstring(L, kind_name(h->model->edge_tag(e).kind));
  lua_setfield(L, -2, "kind");
  return 1;
}

int es_len(lua_State* L) {
  Handle* h = check_handle(L, 1, kEdgeSetType, "#edges", "self");
  check_same_model(h, nullptr, "#edges", "self");
  lua_pushinteger(L, static_cast<lua_Integer>(edgeset_edges(h).size()));
  return 1;
}

int es_count(lua_State* L) {
  lua_pushinteger(L, static_cast<lua_Integer>(self_edges(L, "edges:count").edges.size()));
  return 1;
}

int es_length(lua_State* L) {
  const Self s = self_edges(L, "edges:length");
  double total = 0;
  for (const EdgeRef& e : s.edges) {
    const auto [a, b] = s.model->edge_points(e);
    total += (b - a).norm();
  }
  lua_pushnumber(L, total);
  return 1;
}

int es_blocks(lua_State* L) {
  const Self s = self_edges(L, "edges:blocks");
  std::vector<BlockId> blocks;
  std::set<BlockId> seen;
  for (const EdgeRef& e : s.edges)
    if (seen.insert(e.block).second) blocks.push_back(e.block);
  push_model_of(L, 1);
  push_blockset(L, -1, blocks);
  return 1;
}

// edges:fix(): fixed points at both end points of every edge (once per block
// vertex): the Fixed boundary.
int es_fix(lua_State* L) {
  Self s = self_edges(L, "edges:fix");
  check_not_busy(*s.model, "edges:fix");
  if (s.edges.empty()) fail("edges:fix: the edge set is empty (check the selection that made it)");
  s.model->fix_edges(s.edges);
  return 0;
}

// edges:pressure(p) → Pressure. p: number, {{t, p}, ...} or function(t); Pa,
// positive pushes into the blocks.
int es_pressure(lua_State* L) {
  Self s = self_edges(L, "edges:pressure");
  check_not_busy(*s.model, "edges:pressure");
  if (s.edges.empty()) fail("edges:pressure: the edge set is empty (check the selection that made it)");
  TimeInput p = TimeInput::parse(L, 2, "edges:pressure", "argument 1 (pressure)");
  const int id = s.model->add_pressure(std::move(s.edges), std::move(p), L);
  push_model_of(L, 1);
  push_pressure(L, -1, id);
  return 1;
}

int es_tostring(lua_State* L) {
  auto* h = static_cast<Handle*>(luaL_checkudata(L, 1, kEdgeSetType));
  lua_pushfstring(L, "dda.EdgeSet (%d edges)", static_cast<int>(h->count));
  return 1;
}

}  // namespace

void register_edges(lua_State* L) {
  static const Method model_methods[] = {
      {"edges", guarded<m_edges>,
       "m:edges{...} → EdgeSet\nThe block edges that meet every criterion given (m:edges() every edge).",
       kEdgesOptions},
      {}};
  add_model_methods(L, model_methods, "Edges");
  static const Method methods[] = {
      {"count", guarded<es_count>, "edges:count() → the number of edges (also #edges)"},
      {"length", guarded<es_length>, "edges:length() → their total length (m)"},
      {"blocks", guarded<es_blocks>, "edges:blocks() → BlockSet of the distinct blocks the edges belong to"},
      {"fix", guarded<es_fix>,
       "edges:fix(): fixed points at both end points of every edge (once per block vertex): the Fixed boundary."},
      {"pressure", guarded<es_pressure>,
       "edges:pressure(p) → Pressure. p: number, {{t, p}, ...} or function(t); Pa, positive pushes into the blocks."},
      {}};
  static const luaL_Reg meta[] = {{"__len", guarded<es_len>}, {"__tostring", es_tostring}, {nullptr, nullptr}};
  define_type(L, kEdgeSetType, methods, meta, guarded<es_index>);
}

}  // namespace dda::script
