// dda.RockMaterial and dda.JointMaterial: m:rock{...}, m:joint{...},
// m:default_joint(); fields readable and writable (rock.E = 60e9).
#include <cstring>

#include "wrap.hpp"

namespace dda::script {

namespace {

// m:rock{density = ρ, E = E, nu = ν, mesh_size = h (m; blocks meshed, block/mesh.hpp)} → RockMaterial
int m_rock(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:rock");
  check_not_busy(m, "m:rock");
  const Options o(L, 2, "m:rock", {"density", "E", "nu", "mesh_size"});
  RockMaterial r;
  r.density = o.positive("density");
  r.youngs = o.positive("E");
  r.poisson = o.number("nu");
  if (r.poisson < 0 || r.poisson >= 0.5)
    fail("m:rock: option 'nu' (Poisson's ratio) must lie in [0, 0.5), got ", r.poisson);
  r.mesh_size = o.non_negative("mesh_size", 0);
  const int id = m.world().add_rock_material(r);
  push_rock(L, 1, id);
  return 1;
}

// m:joint{friction = φ (degrees), cohesion = c (Pa), tension = σt (Pa),
//         kn = normal stiffness (Pa/m), ks = shear stiffness (Pa/m)} → JointMaterial
int m_joint(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:joint");
  check_not_busy(m, "m:joint");
  const Options o(L, 2, "m:joint", {"friction", "cohesion", "tension", "kn", "ks"});
  JointMaterial j;
  j.friction_deg = o.number("friction");
  if (j.friction_deg < 0 || j.friction_deg >= 90)
    fail("m:joint: option 'friction' (degrees) must lie in [0, 90), got ", j.friction_deg);
  j.cohesion = o.non_negative("cohesion", 0);
  j.tensile_strength = o.non_negative("tension", 0);
  j.normal_stiffness = o.non_negative("kn", 0);
  j.shear_stiffness = o.non_negative("ks", 0);
  validate(j, m.world().joint_material_count());
  const int id = m.world().add_joint_material(j);
  push_joint(L, 1, id);
  return 1;
}

// m:default_joint() → joint material 0 (φ = 30°, c = 0, σt = 0 unless changed)
int m_default_joint(lua_State* L) {
  check_model(L, 1, "m:default_joint");
  push_joint(L, 1, 0);
  return 1;
}

Handle* self_material(lua_State* L, const char* type, const char* call) {
  Handle* h = check_handle(L, 1, type, call, "self");
  return h;
}

// ---- fields ----------------------------------------------------------------------------

int rock_index(lua_State* L) {
  Handle* h = self_material(L, kRockType, "rock");
  const int id = check_rock(L, 1, h->model, "rock", "self");
  if (lua_type(L, 2) != LUA_TSTRING) return 0;
  const char* k = lua_tostring(L, 2);
  const RockMaterial& r = h->model->world().rock_material(id);
  if (!std::strcmp(k, "density"))
    lua_pushnumber(L, r.density);
  else if (!std::strcmp(k, "E"))
    lua_pushnumber(L, r.youngs);
  else if (!std::strcmp(k, "nu"))
    lua_pushnumber(L, r.poisson);
  else if (!std::strcmp(k, "mesh_size"))
    lua_pushnumber(L, r.mesh_size);
  else if (!std::strcmp(k, "id"))
    lua_pushinteger(L, id);
  else
    return 0;
  return 1;
}

int rock_newindex(lua_State* L) {
  Handle* h = self_material(L, kRockType, "rock");
  const int id = check_rock(L, 1, h->model, "rock", "self");
  check_not_busy(*h->model, "rock");
  const std::string k = lua_type(L, 2) == LUA_TSTRING ? lua_tostring(L, 2) : "?";
  RockMaterial r = h->model->world().rock_material(id);
  const std::string call = msg("rock.", k);
  if (k == "density") {
    if (h->model->world().block_count() > 0)
      fail(call, ": the density cannot change once blocks exist (block masses are fixed when blocks are added)");
    r.density = check_number(L, 3, call, "the value");
  } else if (k == "E") {
    r.youngs = check_number(L, 3, call, "the value");
  } else if (k == "nu") {
    r.poisson = check_number(L, 3, call, "the value");
  } else if (k == "mesh_size") {
    r.mesh_size = check_number(L, 3, call, "the value");  // blocks added from now on
  } else {
    fail("rock: unknown field '", k, "' (fields: density, E, nu, mesh_size)");
  }
  validate(r, id);
  h->model->world().rock_material(id) = r;
  return 0;
}

int joint_index(lua_State* L) {
  Handle* h = self_material(L, kJointType, "joint");
  const int id = check_joint(L, 1, h->model, "joint", "self");
  if (lua_type(L, 2) != LUA_TSTRING) return 0;
  const char* k = lua_tostring(L, 2);
  const JointMaterial& j = h->model->world().joint_material(id);
  if (!std::strcmp(k, "friction"))
    lua_pushnumber(L, j.friction_deg);
  else if (!std::strcmp(k, "cohesion"))
    lua_pushnumber(L, j.cohesion);
  else if (!std::strcmp(k, "tension"))
    lua_pushnumber(L, j.tensile_strength);
  else if (!std::strcmp(k, "kn"))
    lua_pushnumber(L, j.normal_stiffness);
  else if (!std::strcmp(k, "ks"))
    lua_pushnumber(L, j.shear_stiffness);
  else if (!std::strcmp(k, "id"))
    lua_pushinteger(L, id);
  else
    return 0;
  return 1;
}

int joint_newindex(lua_State* L) {
  Handle* h = self_material(L, kJointType, "joint");
  const int id = check_joint(L, 1, h->model, "joint", "self");
  check_not_busy(*h->model, "joint");
  const std::string k = lua_type(L, 2) == LUA_TSTRING ? lua_tostring(L, 2) : "?";
  JointMaterial j = h->model->world().joint_material(id);
  const std::string call = msg("joint.", k);
  if (k == "friction")
    j.friction_deg = check_number(L, 3, call, "the value");
  else if (k == "cohesion")
    j.cohesion = check_number(L, 3, call, "the value");
  else if (k == "tension")
    j.tensile_strength = check_number(L, 3, call, "the value");
  else if (k == "kn")
    j.normal_stiffness = check_number(L, 3, call, "the value");
  else if (k == "ks")
    j.shear_stiffness = check_number(L, 3, call, "the value");
  else
    fail("joint: unknown field '", k, "' (fields: friction, cohesion, tension, kn, ks)");
  validate(j, id);
  h->model->world().joint_material(id) = j;
  return 0;
}

int material_eq(lua_State* L) {
  auto* a = static_cast<Handle*>(lua_touserdata(L, 1));
  auto* b = static_cast<Handle*>(lua_touserdata(L, 2));
  lua_pushboolean(L, a && b && a->model == b->model && a->id == b->id);
  return 1;
}

int rock_tostring(lua_State* L) {
  auto* h = static_cast<Handle*>(luaL_checkudata(L, 1, kRockType));
  if (!h->model || h->model->closed() || h->id >= h->model->world().rock_material_count()) {
    lua_pushliteral(L, "dda.RockMaterial (invalid)");
    return 1;
  }
  const RockMaterial& r = h->model->world().rock_material(h->id);
  lua_pushstring(
      L, msg("dda.RockMaterial ", h->id, " (density ", r.density, " kg/m3, E ", r.youngs, " Pa, nu ", r.poisson, ")")
             .c_str());
  return 1;
}

int joint_tostring(lua_State* L) {
  auto* h = static_cast<Handle*>(luaL_checkudata(L, 1, kJointType));
  if (!h->model || h->model->closed() || h->id >= h->model->world().joint_material_count()) {
    lua_pushliteral(L, "dda.JointMaterial (invalid)");
    return 1;
  }
  const JointMaterial& j = h->model->world().joint_material(h->id);
  lua_pushstring(L, msg("dda.JointMaterial ", h->id, " (friction ", j.friction_deg, " deg, cohesion ", j.cohesion,
                        " Pa, tension ", j.tensile_strength, " Pa)")
                        .c_str());
  return 1;
}

}  // namespace

void register_materials(lua_State* L) {
  static const Method model_methods[] = {
      {"rock", guarded<m_rock>, "m:rock{density = ρ, E = E, nu = ν} → RockMaterial"},
      {"joint", guarded<m_joint>,
       "m:joint{friction = φ (degrees), cohesion = c (Pa), tension = σt (Pa)} → JointMaterial"},
      {"default_joint", guarded<m_default_joint>,
       "m:default_joint() → joint material 0 (φ = 30°, c = 0, σt = 0 unless changed)"},
      {}};
  add_model_methods(L, model_methods);
  static const Method no_methods[] = {{}};
  static const luaL_Reg rock_meta[] = {
      {"__newindex", guarded<rock_newindex>}, {"__eq", material_eq}, {"__tostring", rock_tostring}, {nullptr, nullptr}};
  define_type(L, kRockType, no_methods, rock_meta, guarded<rock_index>);
  static const luaL_Reg joint_meta[] = {{"__newindex", guarded<joint_newindex>},
                                        {"__eq", material_eq},
                                        {"__tostring", joint_tostring},
                                        {nullptr, nullptr}};
  define_type(L, kJointType, no_methods, joint_meta, guarded<joint_index>);
}

}  // namespace dda::script
