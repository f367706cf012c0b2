// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Model geometry: domain, holes (dda.Hole), material regions, joint sets,
// joint lines and block generation through dda::geometry::cut_blocks.
#include <climits>
#include <cmath>

#include "core/memory.hpp"
#include "geometry/cutting.hpp"
#include "wrap.hpp"

namespace dda::script {

namespace {

void check_not_generated(const ScriptModel& m, const char* call) {
  if (m.generated()) fail(call, ": blocks were already generated (m:generate() was called); set up geometry before it");
}

// One outline from an options table: polygon = {...}, box = {x1, y1, x2, y2},
// circle = {x, y, r} (with `segments`, when allowed) or the points inline.
std::vector<Vec2> read_shape(const Options& o, bool allow_circle) {
  lua_State* L = o.state();
  const bool has_inline = o.array_size() > 0;
  const int given = int(o.has("polygon")) + int(o.has("box")) + int(allow_circle && o.has("circle")) + int(has_inline);
  const char* kinds = allow_circle
                          ? "polygon = {{x, y}, ...}, box = {x1, y1, x2, y2}, circle = {x, y, r} or the points inline"
                          : "polygon = {{x, y}, ...}, box = {x1, y1, x2, y2} or the points inline";
  if (given != 1)
    fail(o.call(), ": give the outline once, as ", kinds, given == 0 ? " (none given)" : " (several given)");
  if (has_inline) return check_polygon(L, o.index(), o.call(), "the outline");
  if (o.has("polygon")) return o.polygon("polygon");
  if (o.has("box")) {
    const auto q = o.quad("box");
    if (q[0] == q[2] || q[1] == q[3]) fail(o.call(), ": option 'box' has zero width or height");
    return box_polygon(q);
  }
  // circle
  o.push("circle");
  const int idx = lua_gettop(L);
  if (lua_type(L, idx) != LUA_TTABLE || lua_rawlen(L, idx) != 3) {
    lua_pop(L, 1);
    fail(o.call(), ": option 'circle' must be {x, y, r}");
  }
  double c[3];
  for (int k = 0; k < 3; ++k) {
    lua_rawgeti(L, idx, k + 1);
    const bool ok = lua_type(L, -1) == LUA_TNUMBER && std::isfinite(lua_tonumber(L, -1));
    c[k] = lua_tonumber(L, -1);
    lua_pop(L, 1);
    if (!ok) {
      lua_pop(L, 1);
      fail(o.call(), ": option 'circle' must be {x, y, r} of finite numbers");
    }
  }
  lua_pop(L, 1);
  if (!(c[2] > 0)) fail(o.call(), ": the circle's radius must be positive, got ", c[2]);
  const long n = o.integer("segments", 32);
  if (n < 3) fail(o.call(), ": option 'segments' must be at least 3, got ", n);
  // Refused before the points are made: the cut takes about a kilobyte a segment.
  check_memory_need(geometry::kCutBytesPerCrossing * static_cast<double>(n), memory_headroom(),
                    msg(o.call(), ": a circle of ", n, " segments"), "cutting takes about 1 kB a segment",
                    "give fewer segments (option 'segments', 32 by default)");
  if (n > INT_MAX) fail(o.call(), ": option 'segments' must be at most ", INT_MAX, ", got ", n);
  std::vector<Vec2> pts;
  for (long k = 0; k < n; ++k) {
    const double a = 2 * kPi * double(k) / double(n);
    pts.emplace_back(c[0] + c[2] * std::cos(a), c[1] + c[2] * std::sin(a));
  }
  return pts;
}

int optional_joint(const Options& o, ScriptModel& m, const char* key, int def) {
  if (!o.has(key)) return def;
  o.push(key);
  const int j = check_joint(o.state(), -1, &m, o.call(), msg("option '", key, "'"));
  lua_pop(o.state(), 1);
  return j;
}

int optional_rock(const Options& o, ScriptModel& m, const char* key, int def) {
  if (!o.has(key)) return def;
  o.push(key);
  const int r = check_rock(o.state(), -1, &m, o.call(), msg("option '", key, "'"));
  lua_pop(o.state(), 1);
  return r;
}

constexpr Name kDomainOptions[] = {
    {"polygon", "the outline {{x, y}, ...}; or `box`, or the points inline: m:domain{{x, y}, ...}", "—"},
    {"box", "{x1, y1, x2, y2}: a rectangular outline", "—"},
    {"rock", "the RockMaterial of its blocks (m:region{...} gives others)", "the first rock material"},
    {"joint", "the JointMaterial of the domain's outline edges", "the default joint"}};
constexpr Name kHoleOptions[] = {
    {"polygon", "the outline {{x, y}, ...}; or `box`, `circle`, or the points inline", "—"},
    {"box", "{x1, y1, x2, y2}: a rectangular hole", "—"},
    {"circle", "{x, y, r}: a circular hole, a polygon of `segments` sides", "—"},
    {"segments", "sides of a circle's polygon", "32"},
    {"joint", "the JointMaterial of the hole's outline edges", "the default joint"}};
constexpr Name kRegionOptions[] = {
    {"polygon", "the region {{x, y}, ...}; or `box`, or the points inline", "—"},
    {"box", "{x1, y1, x2, y2}: a rectangular region", "—"},
    {"rock", "the RockMaterial of the blocks whose centroid lies in it (the last region wins)", nullptr}};
constexpr Name kJointSetOptions[] = {
    {"dip", "angle of the joints, degrees counter-clockwise from +x", nullptr},
    {"spacing", "distance between joints, perpendicular to them (m)", nullptr},
    {"origin", "{x, y}: a point one joint passes through", "{0, 0}"},
    {"joint", "the JointMaterial of the set's joints", "the default joint"},
    {"trace", "length of each joint trace (m): non-persistent joints; 0: persistent", "0"},
    {"bridge", "length of rock bridge between traces (m); needs `trace`", "0"},
    {"spacing_sd", "standard deviation of the spacing (m)", "0"},
    {"dip_sd", "standard deviation of the dip (degrees)", "0"},
    {"trace_sd", "standard deviation of the trace length (m)", "0"},
    {"seed", "seed of the set's variations (the same seed, the same joints on any machine)", "0"}};
constexpr Name kJointLineOptions[] = {
    {"from", "{x, y}: one end; or give both ends inline: m:joint_line{{x1, y1}, {x2, y2}}", "—"},
    {"to", "{x, y}: the other end", "—"},
    {"joint", "its JointMaterial", "the default joint"}};
constexpr Name kGenerateOptions[] = {
    {"min_area", "blocks smaller than this (m²) are merged into the neighbour sharing the longest joint", "0"},
    {"slivers", "`\"merge\"` such blocks, or `\"error\"`: report them", "\"merge\""},
    {"snap", "points closer than this (m) become one vertex", "1e-9 × the domain's size"},
    {"inner_cut",
     "a JointMaterial: a hole no joint reaches (or a closed loop of joints) is cut free with short joints of it; "
     "without it such a hole is an error",
     "none"}};
constexpr Name kGenerateReturns[] = {{"blocks", "blocks made"},
                                     {"slivers_merged", "blocks below min_area merged into a neighbour"},
                                     {"dangling_edges_removed", "joint pieces that ended in rock, removed"},
                                     {"inner_cuts", "cuts added by inner_cut"},
                                     {"input_segments", "segments cut (boundaries, holes and joints)"}};

// m:domain{polygon | box | points..., rock = r, joint = j}
int m_domain(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:domain");
  check_not_generated(m, "m:domain");
  const Options o(L, 2, "m:domain", kDomainOptions, true);
  std::vector<Vec2> outline = read_shape(o, false);
  int rock = optional_rock(o, m, "rock", -1);
  if (rock < 0) {
    if (m.world().rock_material_count() == 0)
      fail("m:domain: no rock material yet: create one with m:rock{...} first, or pass rock = ...");
    rock = 0;
  }
  const int joint = optional_joint(o, m, "joint", 0);
  m.set_domain(std::move(outline), rock, joint);
  return 0;
}

// m:hole{polygon | box | circle | points..., segments = 32, joint = j} → dda.Hole
int m_hole(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:hole");
  check_not_generated(m, "m:hole");
  const Options o(L, 2, "m:hole", kHoleOptions, true);
  std::vector<Vec2> outline = read_shape(o, true);
  if (!o.has("circle") && o.has("segments")) fail("m:hole: option 'segments' only applies to circle = {x, y, r}");
  const int joint = optional_joint(o, m, "joint", 0);
  const int id = m.add_hole(std::move(outline), joint);
  push_hole(L, 1, id);
  return 1;
}

// m:region{polygon | box | points..., rock = r}
int m_region(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:region");
  check_not_generated(m, "m:region");
  const Options o(L, 2, "m:region", kRegionOptions, true);
  geometry::MaterialRegion region;
  region.polygon = read_shape(o, false);
  if (!o.has("rock")) fail("m:region: option 'rock' is required (the rock material of the region's blocks)");
  region.rock_material = optional_rock(o, m, "rock", 0);
  m.cut_input().regions.push_back(std::move(region));
  return 0;
}

// m:joint_set{dip, spacing, origin, joint, trace, bridge, spacing_sd, dip_sd, trace_sd, seed} → set number
int m_joint_set(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:joint_set");
  check_not_generated(m, "m:joint_set");
  const Options o(L, 2, "m:joint_set", kJointSetOptions);
  geometry::JointSet s;
  s.dip_deg = o.number("dip");
  s.spacing = o.positive("spacing");
  s.origin = o.point("origin", Vec2::Zero());
  s.joint_material = optional_joint(o, m, "joint", 0);
  s.trace_length = o.non_negative("trace", 0);
  s.bridge_length = o.non_negative("bridge", 0);
  if (o.has("bridge") && s.trace_length == 0)
    fail("m:joint_set: option 'bridge' needs 'trace' (the length of each joint trace)");
  s.spacing_sd = o.non_negative("spacing_sd", 0);
  s.dip_sd_deg = o.non_negative("dip_sd", 0);
  s.trace_sd = o.non_negative("trace_sd", 0);
  const long seed = o.integer("seed", 0);
  if (seed < 0) fail("m:joint_set: option 'seed' must be zero or positive, got ", seed);
  s.seed = static_cast<std::uint64_t>(seed);
  m.cut_input().sets.push_back(s);
  lua_pushinteger(L, static_cast<lua_Integer>(m.cut_input().sets.size()));
  return 1;
}

// m:joint_line{from = {x, y}, to = {x, y}, joint = j}  or  m:joint_line{{x1, y1}, {x2, y2}, joint = j}
int m_joint_line(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:joint_line");
  check_not_generated(m, "m:joint_line");
  const Options o(L, 2, "m:joint_line", kJointLineOptions, true);
  geometry::JointLine line;
  if (o.array_size() > 0) {
    if (o.has("from") || o.has("to")) fail("m:joint_line: give the end points either inline or as from/to, not both");
    if (o.array_size() != 2) fail("m:joint_line: expected two end points {x1, y1}, {x2, y2}, got ", o.array_size());
    lua_rawgeti(L, o.index(), 1);
    line.a = check_point(L, -1, "m:joint_line", "end point 1");
    lua_pop(L, 1);
    lua_rawgeti(L, o.index(), 2);
    line.b = check_point(L, -1, "m:joint_line", "end point 2");
    lua_pop(L, 1);
  } else {
    line.a = o.point("from");
    line.b = o.point("to");
  }
  if (line.a == line.b) fail("m:joint_line: the two end points are the same point");
  line.joint_material = optional_joint(o, m, "joint", 0);
  m.cut_input().lines.push_back(line);
  return 0;
}

// m:generate{min_area, slivers = "merge" | "error", snap, inner_cut = joint} → BlockSet, info
int m_generate(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:generate");
  check_not_busy(m, "m:generate");
  check_not_generated(m, "m:generate");
  if (!m.has_domain()) fail("m:generate: no domain: call m:domain{...} first");
  geometry::CutInput& in = m.cut_input();
  if (!lua_isnoneornil(L, 2)) {
    const Options o(L, 2, "m:generate", kGenerateOptions);
    in.min_block_area = o.non_negative("min_area", in.min_block_area);
    if (o.has("slivers")) {
      const std::string p = o.string("slivers");
      if (p == "merge")
        in.sliver_policy = geometry::SliverPolicy::Merge;
      else if (p == "error")
        in.sliver_policy = geometry::SliverPolicy::Error;
      else
        fail("m:generate: option 'slivers' must be \"merge\" or \"error\", got \"", p, "\"");
    }
    in.snap_tolerance = o.non_negative("snap", in.snap_tolerance);
    in.inner_cut_material = optional_joint(o, m, "inner_cut", in.inner_cut_material);
  }
  std::vector<BlockId> ids;
  try {
    ids = m.generate();
  } catch (const Error& e) {
    // The engine names its own inputs; a script gives them as these options.
    static const std::pair<std::string, std::string> kLuaNames[] = {
        {"set inner_cut_material to", "give inner_cut = a joint material to"}, {"min_block_area", "min_area"}};
    std::string text = e.what();
    for (const auto& [engine, lua] : kLuaNames)
      for (auto at = text.find(engine); at != std::string::npos; at = text.find(engine, at + lua.size()))
        text.replace(at, engine.size(), lua);
    fail("m:generate: ", text);
  }
  push_blockset(L, 1, ids);
  const geometry::CutStats& st = m.cut_stats();
  lua_createtable(L, 0, 5);
  lua_pushinteger(L, static_cast<lua_Integer>(ids.size()));
  lua_setfield(L, -2, "blocks");
  lua_pushinteger(L, st.slivers_merged);
  lua_setfield(L, -2, "slivers_merged");
  lua_pushinteger(L, st.dangling_edges_removed);
  lua_setfield(L, -2, "dangling_edges_removed");
  lua_pushinteger(L, st.inner_cuts);
  lua_setfield(L, -2, "inner_cuts");
  lua_pushinteger(L, st.input_segments);
  lua_setfield(L, -2, "input_segments");
  return 2;
}

// ---- dda.Hole ----------------------------------------------------------------------------------

// hole:edges() → EdgeSet of the hole's boundary edges (after m:generate()).
int hole_edges(lua_State* L) {
  Handle* h = check_handle(L, 1, kHoleType, "hole:edges", "self");
  if (!h->model->generated()) fail("hole:edges: no blocks yet: call m:generate() first");
  EdgeQuery q;
  q.hole = h->id;
  const std::vector<EdgeRef> edges = select_edges(*h->model, q);
  push_model_of(L, 1);
  push_edgeset(L, -1, edges);
  return 1;
}

// hole:number() → 1-based hole number (as in messages: "hole 1")
int hole_number(lua_State* L) {
  Handle* h = check_handle(L, 1, kHoleType, "hole:number", "self");
  lua_pushinteger(L, h->id + 1);
  return 1;
}

int hole_tostring(lua_State* L) {
  auto* h = static_cast<Handle*>(luaL_checkudata(L, 1, kHoleType));
  lua_pushfstring(L, "dda.Hole %d", static_cast<int>(h->id + 1));
  return 1;
}

}  // namespace

void register_geometry(lua_State* L) {
  static const Method model_methods[] = {
      {"domain", guarded<m_domain>,
       "m:domain{...}\nThe region cut into blocks by the joint sets and lines (once, before m:generate).",
       kDomainOptions},
      {"hole", guarded<m_hole>, "m:hole{...} → Hole\nAn excavation: no blocks inside it.", kHoleOptions},
      {"region", guarded<m_region>, "m:region{...}\nA material region: its blocks get its rock.", kRegionOptions},
      {"joint_set", guarded<m_joint_set>,
       "m:joint_set{...} → the set's number\nParallel joints across the domain; persistent, or traces and bridges "
       "from a random phase.",
       kJointSetOptions},
      {"joint_line", guarded<m_joint_line>, "m:joint_line{...}\nOne joint along a segment.", kJointLineOptions},
      {"generate", guarded<m_generate>,
       "m:generate{...} → BlockSet, info\nCuts the domain into blocks (docs/formulation.md, \"Block generation\"); "
       "`info` says what the cut did.",
       kGenerateOptions, kGenerateReturns},
      {}};
  add_model_methods(L, model_methods, "Geometry");
  static const Method hole_methods[] = {
      {"edges", guarded<hole_edges>, "hole:edges() → EdgeSet of the hole's boundary edges (after m:generate())."},
      {"number", guarded<hole_number>, "hole:number() → 1-based hole number (as in messages: \"hole 1\")"},
      {}};
  static const luaL_Reg hole_meta[] = {{"__tostring", hole_tostring}, {nullptr, nullptr}};
  define_type(L, kHoleType, hole_methods, hole_meta);
}

}  // namespace dda::script
