// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Shared wrapper machinery: type registration, handles and their checks,
// edge selection.
#include "wrap.hpp"

#include "live_server.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <thread>

namespace dda::script {

namespace {

// Short human names for messages: "dda.Block" → "block".
std::string pretty(const char* type) {
  if (std::strcmp(type, kModelType) == 0) return "model";
  if (std::strcmp(type, kBlockType) == 0) return "block";
  if (std::strcmp(type, kBlockSetType) == 0) return "block set";
  if (std::strcmp(type, kEdgeSetType) == 0) return "edge set";
  if (std::strcmp(type, kRockType) == 0) return "rock material";
  if (std::strcmp(type, kJointType) == 0) return "joint material";
  if (std::strcmp(type, kMonitorType) == 0) return "monitor";
  if (std::strcmp(type, kPointLoadType) == 0) return "point load";
  if (std::strcmp(type, kPressureType) == 0) return "pressure";
  if (std::strcmp(type, kHoleType) == 0) return "hole";
  return type;
}

// The type's name with its article: "a block", "an edge set".
std::string a_pretty(const char* type) {
  const std::string name = pretty(type);
  return (std::strchr("aeiou", name[0]) ? "an " : "a ") + name;
}

// __index: methods first, then the type's fallback (fields), else an error
// naming the key (a misspelt method is caught where it is written).
int index_dispatch(lua_State* L) {
  lua_pushvalue(L, 2);
  if (lua_rawget(L, lua_upvalueindex(1)) != LUA_TNIL) return 1;
  lua_pop(L, 1);
  if (!lua_isnone(L, lua_upvalueindex(2))) {
    // Fields (and, for sets, integer indices: s[i] is nil past the end so
    // that ipairs stops).
    const lua_CFunction fallback = lua_tocfunction(L, lua_upvalueindex(2));
    const int n = fallback(L);
    if (n > 0 && (!lua_isnil(L, -1) || lua_type(L, 2) != LUA_TSTRING)) return n;
    lua_settop(L, 2);
  }
  const char* type = "object";
  if (lua_getmetatable(L, 1)) {
    lua_getfield(L, -1, "__name");
    if (lua_type(L, -1) == LUA_TSTRING) type = lua_tostring(L, -1);  // kept alive by the metatable
    lua_pop(L, 2);
  }
  if (lua_type(L, 2) != LUA_TSTRING) return luaL_error(L, "%s cannot be indexed with a %s", type, luaL_typename(L, 2));
  const char* key = lua_tostring(L, 2);
  // "did you mean": the closest method name.
  const char* best = nullptr;
  int best_d = 3;
  lua_pushnil(L);
  while (lua_next(L, lua_upvalueindex(1)) != 0) {
    lua_pop(L, 1);
    if (lua_type(L, -1) == LUA_TSTRING) {
      const int d = edit_distance(key, lua_tostring(L, -1));
      if (d < best_d) best_d = d, best = lua_tostring(L, -1);  // the key string lives in the methods table
    }
  }
  if (best) return luaL_error(L, "%s has no method or field '%s' (did you mean '%s'?)", type, key, best);
  return luaL_error(L, "%s has no method or field '%s'", type, key);
}

}  // namespace

namespace {

// registry[&kApiKey] = {docs = {[function] = Method*}, owners = {"dda", ...},
//                       [owner] = {Method*, ...}, topics = {[Method*] = topic},
//                       fields = {[owner] = {data, size}}}
const char kApiKey = 0;

void push_api(lua_State* L) {
  if (lua_rawgetp(L, LUA_REGISTRYINDEX, &kApiKey) == LUA_TTABLE) return;
  lua_pop(L, 1);
  lua_createtable(L, 0, 4);
  lua_newtable(L);
  lua_setfield(L, -2, "docs");
  lua_newtable(L);
  lua_setfield(L, -2, "owners");
  lua_newtable(L);
  lua_setfield(L, -2, "fields");
  lua_newtable(L);
  lua_setfield(L, -2, "topics");
  lua_pushvalue(L, -1);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kApiKey);
}

// Pushes api[owner] (created, and owner appended to api.owners, on first use).
void push_owner(lua_State* L, const char* owner) {
  push_api(L);
  if (lua_getfield(L, -1, owner) != LUA_TTABLE) {
    lua_pop(L, 1);
    lua_newtable(L);
    lua_pushvalue(L, -1);
    lua_setfield(L, -3, owner);
    lua_getfield(L, -2, "owners");
    lua_pushstring(L, owner);
    lua_rawseti(L, -2, static_cast<lua_Integer>(lua_rawlen(L, -2)) + 1);
    lua_pop(L, 1);
  }
  lua_remove(L, -2);
}

}  // namespace

void set_methods(lua_State* L, const Method* methods, const char* owner, const char* topic) {
  const int t = lua_absindex(L, -1);
  if (topic) {
    push_api(L);
    lua_getfield(L, -1, "topics");
    for (const Method* m = methods; m && m->name; ++m) {
      lua_pushstring(L, topic);
      lua_rawsetp(L, -2, m);
    }
    lua_pop(L, 2);
  }
  push_owner(L, owner);
  push_api(L);
  lua_getfield(L, -1, "docs");
  lua_remove(L, -2);
  for (const Method* m = methods; m && m->name; ++m) {
    DDA_ASSERT(m->doc != nullptr, "a function of the API without its documentation");
    lua_pushcfunction(L, m->func);
    lua_pushvalue(L, -1);
    lua_setfield(L, t, m->name);
    lua_pushlightuserdata(L, const_cast<Method*>(m));
    lua_rawset(L, -3);  // docs[function] = Method*
    lua_pushlightuserdata(L, const_cast<Method*>(m));
    lua_rawseti(L, -3, static_cast<lua_Integer>(lua_rawlen(L, -3)) + 1);
  }
  lua_pop(L, 2);
}

const Method* find_method(lua_State* L, int idx) {
  idx = lua_absindex(L, idx);
  push_api(L);
  lua_getfield(L, -1, "docs");
  lua_pushvalue(L, idx);
  lua_rawget(L, -2);
  const auto* m = static_cast<const Method*>(lua_touserdata(L, -1));
  lua_pop(L, 3);
  return m;
}

std::vector<ApiSection> api_sections(lua_State* L) {
  std::vector<ApiSection> out;
  push_api(L);
  lua_getfield(L, -1, "owners");
  const auto n = static_cast<lua_Integer>(lua_rawlen(L, -1));
  for (lua_Integer i = 1; i <= n; ++i) {
    lua_rawgeti(L, -1, i);
    ApiSection section;
    section.owner = lua_tostring(L, -1);
    lua_getfield(L, -3, section.owner.c_str());
    const auto count = static_cast<lua_Integer>(lua_rawlen(L, -1));
    lua_getfield(L, -4, "topics");
    for (lua_Integer k = 1; k <= count; ++k) {
      lua_rawgeti(L, -2, k);
      const auto* m = static_cast<const Method*>(lua_touserdata(L, -1));
      section.methods.push_back(m);
      lua_rawgetp(L, -2, m);
      section.topics.push_back(lua_isstring(L, -1) ? lua_tostring(L, -1) : "");
      lua_pop(L, 2);
    }
    lua_pop(L, 2);
    lua_getfield(L, -3, "fields");
    if (lua_getfield(L, -1, section.owner.c_str()) == LUA_TTABLE) {
      lua_rawgeti(L, -1, 1);
      lua_rawgeti(L, -2, 2);
      section.fields = Names(static_cast<const Name*>(lua_touserdata(L, -2)), lua_tointeger(L, -1));
      lua_pop(L, 2);
    }
    lua_pop(L, 3);
    out.push_back(std::move(section));
  }
  lua_pop(L, 2);
  return out;
}

void define_type(lua_State* L, const char* type, const Method* methods, const luaL_Reg* meta,
                 lua_CFunction index_fallback, Names fields) {
  luaL_newmetatable(L, type);
  lua_newtable(L);
  set_methods(L, methods, type);
  lua_pushvalue(L, -1);
  lua_setfield(L, -3, "__methods");
  if (index_fallback) {
    lua_pushcfunction(L, index_fallback);
    lua_pushcclosure(L, index_dispatch, 2);
  } else {
    lua_pushcclosure(L, index_dispatch, 1);
  }
  lua_setfield(L, -2, "__index");
  if (meta) luaL_setfuncs(L, meta, 0);
  // Scripts cannot reach the metatable (getmetatable returns this text):
  // getmetatable(m).__gc(m) would delete a model that handles still use.
  lua_pushstring(L, type);
  lua_setfield(L, -2, "__metatable");
  lua_pop(L, 1);
  if (!fields.empty()) {
    push_api(L);
    lua_getfield(L, -1, "fields");
    lua_createtable(L, 2, 0);
    lua_pushlightuserdata(L, const_cast<Name*>(fields.data()));
    lua_rawseti(L, -2, 1);
    lua_pushinteger(L, static_cast<lua_Integer>(fields.size()));
    lua_rawseti(L, -2, 2);
    lua_setfield(L, -2, type);
    lua_pop(L, 2);
  }
}

void add_methods(lua_State* L, const char* type, const Method* methods, const char* topic) {
  luaL_getmetatable(L, type);
  lua_getfield(L, -1, "__methods");
  set_methods(L, methods, type, topic);
  lua_pop(L, 2);
}

void add_model_methods(lua_State* L, const Method* methods, const char* topic) {
  add_methods(L, kModelType, methods, topic);
}

// ---- models ---------------------------------------------------------------------------

ScriptModel& push_new_model(lua_State* L, const Controls& controls) {
  return push_model(L, std::make_unique<ScriptModel>(controls));
}

ScriptModel& push_model(lua_State* L, std::unique_ptr<ScriptModel> model) {
  auto* box = static_cast<ModelBox*>(lua_newuserdatauv(L, sizeof(ModelBox), 0));
  box->model = nullptr;
  luaL_setmetatable(L, kModelType);  // its __gc deletes the model
  box->model = model.release();
  show_live(L, *box->model);
  return *box->model;
}

ScriptModel& check_model(lua_State* L, int idx, std::string_view call) {
  auto* box = static_cast<ModelBox*>(luaL_testudata(L, idx, kModelType));
  if (!box || !box->model)
    fail(call, ": expected a model as self, got ", type_of(L, idx),
         " (call methods with a colon: m:step(10), not m.step(10))");
  if (box->model->closed()) fail(call, ": attempt to use a closed model (m:close() was called)");
  hold_for_call(*box->model);
  return *box->model;
}

void check_not_busy(const ScriptModel& m, std::string_view call) {
  if (m.busy()) fail(call, ": the model cannot be changed or stepped from inside a load history function");
  const RunControl& c = *m.shared_control();
  if (c.state() == RunState::Running && c.background() && c.stepping_thread() != std::this_thread::get_id())
    fail(call,
         ": the model is running in the background: m:pause() it first (m:resume() goes on), or m:wait() "
         "for the run to end");
}

// ---- handles ------------------------------------------------------------------------------

Handle* push_handle(lua_State* L, int model_idx, const char* type, int id, int extra_bytes) {
  model_idx = lua_absindex(L, model_idx);
  auto* box = static_cast<ModelBox*>(lua_touserdata(L, model_idx));
  auto* h = static_cast<Handle*>(lua_newuserdatauv(L, sizeof(Handle) + extra_bytes, 1));
  h->model = box->model;
  h->id = id;
  h->count = 0;
  luaL_setmetatable(L, type);
  lua_pushvalue(L, model_idx);
  lua_setiuservalue(L, -2, 1);
  return h;
}

Handle* test_handle(lua_State* L, int idx, const char* type) {
  return static_cast<Handle*>(luaL_testudata(L, idx, type));
}

Handle* check_handle(lua_State* L, int idx, const char* type, std::string_view call, std::string_view what) {
  Handle* h = test_handle(L, idx, type);
  if (!h) {
    if (what == "self")
      fail(call, ": expected ", a_pretty(type), " as self, got ", type_of(L, idx),
           " (call methods with a colon: x:method(...))");
    fail(call, ": ", what, " must be ", a_pretty(type), ", got ", type_of(L, idx));
  }
  if (!h->model || h->model->closed())
    fail(call, ": attempt to use ", a_pretty(type), " of a closed model (m:close() was called)");
  hold_for_call(*h->model);
  return h;
}

void push_model_of(lua_State* L, int idx) { lua_getiuservalue(L, idx, 1); }

void check_same_model(const Handle* h, const ScriptModel* model, std::string_view call, std::string_view what) {
  if (!h->model || h->model->closed()) fail(call, ": attempt to use ", what, " of a closed model");
  if (model && h->model != model) fail(call, ": ", what, " belongs to another model");
}

void push_block(lua_State* L, int model_idx, BlockId b) { push_handle(L, model_idx, kBlockType, b); }

BlockId check_block(lua_State* L, int idx, const ScriptModel* model, std::string_view call, std::string_view what) {
  Handle* h = check_handle(L, idx, kBlockType, call, what);
  check_same_model(h, model, call, what);
  if (h->id < 0 || static_cast<std::size_t>(h->id) >= h->model->world().block_count())
    fail(call, ": attempt to use a removed/invalid block (id ", h->id, ")");
  return h->id;
}

void push_blockset(lua_State* L, int model_idx, std::span<const BlockId> blocks) {
  Handle* h = push_handle(L, model_idx, kBlockSetType, 0, static_cast<int>(blocks.size() * sizeof(BlockId)));
  h->count = static_cast<std::int32_t>(blocks.size());
  std::copy(blocks.begin(), blocks.end(), set_blocks(h));
}

std::vector<BlockId> check_blockset(lua_State* L, int idx, const ScriptModel* model, std::string_view call,
                                    std::string_view what) {
  if (test_handle(L, idx, kBlockType)) return {check_block(L, idx, model, call, what)};
  Handle* h = check_handle(L, idx, kBlockSetType, call, what);
  check_same_model(h, model, call, what);
  std::vector<BlockId> out(set_blocks(h), set_blocks(h) + h->count);
  for (BlockId b : out)
    if (static_cast<std::size_t>(b) >= h->model->world().block_count())
      fail(call, ": attempt to use a removed/invalid block (id ", b, ")");
  return out;
}

// An edge set's id is the model's mesh generation when it was made: a set
// taken before the wave model meshed the blocks stands for the element
// edges along its edges now.
void push_edgeset(lua_State* L, int model_idx, std::span<const EdgeRef> edges) {
  auto* box = static_cast<ModelBox*>(lua_touserdata(L, model_idx));
  const int generation = box && box->model && !box->model->closed() ? box->model->world().mesh_generation() : 0;
  Handle* h = push_handle(L, model_idx, kEdgeSetType, generation, static_cast<int>(edges.size() * sizeof(EdgeRef)));
  h->count = static_cast<std::int32_t>(edges.size());
  std::copy(edges.begin(), edges.end(), set_edges(h));
}

std::vector<EdgeRef> edgeset_edges(const Handle* h) {
  const auto* first = set_edges(const_cast<Handle*>(h));
  std::vector<EdgeRef> stored(first, first + h->count);
  const World& w = h->model->world();
  if (h->id == w.mesh_generation()) return stored;
  std::vector<EdgeRef> now;
  for (const EdgeRef& e : stored)
    for (const EdgeRef& p : w.edges_since_meshing(e)) now.push_back(p);
  return now;
}

std::vector<EdgeRef> check_edgeset(lua_State* L, int idx, const ScriptModel* model, std::string_view call,
                                   std::string_view what) {
  Handle* h = check_handle(L, idx, kEdgeSetType, call, what);
  check_same_model(h, model, call, what);
  std::vector<EdgeRef> out = edgeset_edges(h);
  for (const EdgeRef& e : out)
    if (static_cast<std::size_t>(e.block) >= h->model->world().block_count())
      fail(call, ": attempt to use a removed/invalid block (id ", e.block, ")");
  return out;
}

int check_rock(lua_State* L, int idx, const ScriptModel* model, std::string_view call, std::string_view what) {
  Handle* h = check_handle(L, idx, kRockType, call, what);
  check_same_model(h, model, call, what);
  if (h->id < 0 || h->id >= h->model->world().rock_material_count())
    fail(call, ": attempt to use an invalid rock material (id ", h->id, ")");
  return h->id;
}

int check_joint(lua_State* L, int idx, const ScriptModel* model, std::string_view call, std::string_view what) {
  Handle* h = check_handle(L, idx, kJointType, call, what);
  check_same_model(h, model, call, what);
  if (h->id < 0 || h->id >= h->model->world().joint_material_count())
    fail(call, ": attempt to use an invalid joint material (id ", h->id, ")");
  return h->id;
}

void push_rock(lua_State* L, int model_idx, int id) { push_handle(L, model_idx, kRockType, id); }
void push_joint(lua_State* L, int model_idx, int id) { push_handle(L, model_idx, kJointType, id); }
void push_monitor(lua_State* L, int model_idx, int id) { push_handle(L, model_idx, kMonitorType, id); }
void push_point_load(lua_State* L, int model_idx, int id) { push_handle(L, model_idx, kPointLoadType, id); }
void push_pressure(lua_State* L, int model_idx, int id) { push_handle(L, model_idx, kPressureType, id); }
void push_hole(lua_State* L, int model_idx, int id) { push_handle(L, model_idx, kHoleType, id); }

// ---- edge selection -------------------------------------------------------------------------

namespace {
double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 e = b - a;
  const double len2 = e.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(e) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * e)).norm();
}
bool in_box(const Vec2& p, const std::array<double, 4>& q, double tol) {
  const double x1 = std::min(q[0], q[2]), x2 = std::max(q[0], q[2]);
  const double y1 = std::min(q[1], q[3]), y2 = std::max(q[1], q[3]);
  return p.x() >= x1 - tol && p.x() <= x2 + tol && p.y() >= y1 - tol && p.y() <= y2 + tol;
}
}  // namespace

std::vector<EdgeRef> select_edges(const ScriptModel& m, const EdgeQuery& q) {
  std::vector<EdgeRef> out;
  const World& w = m.world();
  const double tol = q.tol >= 0 ? q.tol : 1e-7 * std::max(1.0, m.extent());
  const auto count = static_cast<BlockId>(w.block_count());
  for (BlockId b = 0; b < count; ++b) {
    if (q.block && *q.block != b) continue;
    const int n = m.edge_count(b);
    for (int k = 0; k < n; ++k) {
      const EdgeRef e{b, k};
      const EdgeTag& tag = m.edge_tag(e);
      if (q.any_boundary && tag.kind != EdgeKind::Domain && tag.kind != EdgeKind::Hole) continue;
      if (q.boundary && tag.kind != *q.boundary) continue;
      if (q.hole >= 0 && (tag.kind != EdgeKind::Hole || tag.hole != q.hole)) continue;
      if (q.joint >= 0 && w.block_edge_joint(b, k) != q.joint) continue;
      if (q.on_segment || q.in_box) {
        const auto [a, c] = m.edge_points(e);
        if (q.on_segment) {
          const Vec2 s0((*q.on_segment)[0], (*q.on_segment)[1]), s1((*q.on_segment)[2], (*q.on_segment)[3]);
          if (distance_to_segment(a, s0, s1) > tol || distance_to_segment(c, s0, s1) > tol) continue;
        }
        if (q.in_box && !(in_box(a, *q.in_box, tol) && in_box(c, *q.in_box, tol))) continue;
      }
      out.push_back(e);
    }
  }
  return out;
}

void push_point(lua_State* L, const Vec2& p) {
  lua_createtable(L, 2, 0);
  lua_pushnumber(L, p.x());
  lua_rawseti(L, -2, 1);
  lua_pushnumber(L, p.y());
  lua_rawseti(L, -2, 2);
}

void set_number_field(lua_State* L, const char* key, double value) {
  lua_pushnumber(L, value);
  lua_setfield(L, -2, key);
}

void set_integer_field(lua_State* L, const char* key, long value) {
  lua_pushinteger(L, value);
  lua_setfield(L, -2, key);
}

void push_stats(lua_State* L, const StepStats& s) {
  lua_createtable(L, 0, 16);
  auto num = [&](const char* k, double v) { set_number_field(L, k, v); };
  auto integer = [&](const char* k, long v) { set_integer_field(L, k, v); };
  num("dt", s.dt);
  integer("open_close_iterations", s.open_close_iterations);
  integer("cg_iterations", s.cg_iterations);
  integer("patch_iterations", s.patch_iterations);
  lua_pushstring(L, s.solver);
  lua_setfield(L, -2, "solver");
  integer("factorisations", s.factorisations);
  integer("factor_iterations", s.factor_iterations);
  lua_pushstring(L, s.solve_regime);
  lua_setfield(L, -2, "solve_regime");
  integer("step_cuts", s.step_cuts);
  lua_pushstring(L, s.cut_reason.c_str());
  lua_setfield(L, -2, "cut_reason");
  integer("contacts", s.contacts);
  integer("closed_contacts", s.closed_contacts);
  lua_pushboolean(L, s.contacts_searched);
  lua_setfield(L, -2, "contacts_searched");
  num("max_displacement_ratio", s.max_displacement_ratio);
  integer("landings", s.landings);
  // Seconds per stage of the step (Stage, world/step_profile.hpp): t_detect, ...
  for (int k = 0; k < kStageCount; ++k) num(("t_" + std::string(kStageKeys[k])).c_str(), s.profile.seconds[k]);
  num("t_total", s.profile.total);
}

}  // namespace dda::script
