// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// dda.RockMaterial and dda.JointMaterial: m:rock{...}, m:joint{...},
// m:default_joint(); fields readable and writable (rock.E = 60e9).
#include <cstring>

#include "wrap.hpp"

namespace dda::script {

namespace {

// The fields of each material: read and written by name (rock.E = 60e9),
// the same table as their options in m:rock{...} and m:joint{...}.
struct RockField {
  Name name;
  double RockMaterial::*value;
};
constexpr RockField kRockFields[] = {
    {{"density", "ρ (kg/m³); fixed once blocks exist (their masses are)", nullptr}, &RockMaterial::density},
    {{"E", "Young's modulus (Pa)", nullptr}, &RockMaterial::youngs},
    {{"nu", "Poisson's ratio, in [0, 0.5)", nullptr}, &RockMaterial::poisson},
    {{"mesh_size",
      "element size (m) of the blocks of this rock, meshed when added (docs/meshed_blocks.md); 0: "
      "first-order blocks",
      "0"},
     &RockMaterial::mesh_size}};
struct JointField {
  Name name;
  double JointMaterial::*value;
};
constexpr JointField kJointFields[] = {
    {{"friction", "friction angle φ (degrees), in [0, 90)", nullptr}, &JointMaterial::friction_deg},
    {{"cohesion", "c (Pa); an intact joint holds shear up to c·L + N·tanφ", "0"}, &JointMaterial::cohesion},
    {{"tension", "tensile strength σt (Pa); an intact joint holds tension up to σt·L", "0"},
     &JointMaterial::tensile_strength},
    {{"kn",
      "the joint's normal stiffness (Pa/m): a contact standing for a length L of joint gets the spring k_n·L; 0: "
      "the contact spring g0",
      "0"},
     &JointMaterial::normal_stiffness},
    {{"ks", "the joint's shear stiffness (Pa/m), k_s·L; 0: shear_ratio × k_n (or × g0 without k_n); needs kn", "0"},
     &JointMaterial::shear_stiffness}};

template <class Field, std::size_t N>
std::vector<Name> names_of(const Field (&fields)[N], const char* id_doc) {
  std::vector<Name> n;
  for (const Field& f : fields) n.push_back(f.name);
  if (id_doc) n.push_back({"id", id_doc});
  return n;
}
const std::vector<Name> kRockOptions = names_of(kRockFields, nullptr);
const std::vector<Name> kJointOptions = names_of(kJointFields, nullptr);
const std::vector<Name> kRockFieldNames = names_of(kRockFields, "its id (read only)");
const std::vector<Name> kJointFieldNames = names_of(kJointFields, "its id (read only; 0: the default joint)");

template <class Field, std::size_t N>
std::string field_names(const Field (&fields)[N]) {
  std::string s;
  for (const Field& f : fields) s.append(s.empty() ? "" : ", ").append(f.name.name);
  return s;
}

// m:rock{density, E, nu, mesh_size} → RockMaterial
int m_rock(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:rock");
  check_not_busy(m, "m:rock");
  const Options o(L, 2, "m:rock", kRockOptions);
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

// m:joint{friction, cohesion, tension, kn, ks} → JointMaterial
int m_joint(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:joint");
  check_not_busy(m, "m:joint");
  const Options o(L, 2, "m:joint", kJointOptions);
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

// ---- fields ----------------------------------------------------------------------------

// __index of a material: its field `key` (or its id), nil for other keys.
template <class Material, class Field, std::size_t N>
int push_field(lua_State* L, const Material& material, int id, const Field (&fields)[N]) {
  if (lua_type(L, 2) != LUA_TSTRING) return 0;
  const std::string_view key = lua_tostring(L, 2);
  if (key == "id") {
    lua_pushinteger(L, id);
    return 1;
  }
  for (const Field& f : fields)
    if (key == f.name.name) {
      lua_pushnumber(L, material.*f.value);
      return 1;
    }
  return 0;
}

// __newindex of a material: sets field `key` (the caller validates).
template <class Material, class Field, std::size_t N>
void set_field(lua_State* L, Material& material, const Field (&fields)[N], const char* what) {
  const std::string key = lua_type(L, 2) == LUA_TSTRING ? lua_tostring(L, 2) : "?";
  for (const Field& f : fields)
    if (key == f.name.name) {
      material.*f.value = check_number(L, 3, msg(what, ".", key), "the value");
      return;
    }
  fail(what, ": unknown field '", key, "' (fields: ", field_names(fields), ")");
}

int rock_index(lua_State* L) {
  Handle* h = check_handle(L, 1, kRockType, "rock", "self");
  const int id = check_rock(L, 1, h->model, "rock", "self");
  return push_field(L, h->model->world().rock_material(id), id, kRockFields);
}

int rock_newindex(lua_State* L) {
  Handle* h = check_handle(L, 1, kRockType, "rock", "self");
  const int id = check_rock(L, 1, h->model, "rock", "self");
  check_not_busy(*h->model, "rock");
  RockMaterial r = h->model->world().rock_material(id);
  if (lua_type(L, 2) == LUA_TSTRING && std::strcmp(lua_tostring(L, 2), "density") == 0 &&
      h->model->world().block_count() > 0)
    fail("rock.density: the density cannot change once blocks exist (block masses are fixed when blocks are added)");
  set_field(L, r, kRockFields, "rock");
  validate(r, id);
  h->model->world().rock_material(id) = r;
  return 0;
}

int joint_index(lua_State* L) {
  Handle* h = check_handle(L, 1, kJointType, "joint", "self");
  const int id = check_joint(L, 1, h->model, "joint", "self");
  return push_field(L, h->model->world().joint_material(id), id, kJointFields);
}

int joint_newindex(lua_State* L) {
  Handle* h = check_handle(L, 1, kJointType, "joint", "self");
  const int id = check_joint(L, 1, h->model, "joint", "self");
  check_not_busy(*h->model, "joint");
  JointMaterial j = h->model->world().joint_material(id);
  set_field(L, j, kJointFields, "joint");
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
  lua_pushstring(
      L, msg("dda.JointMaterial ", h->id, " (friction ", j.friction_deg, " deg, cohesion ", j.cohesion, " Pa, tension ",
             j.tensile_strength, " Pa, kn ", j.normal_stiffness, " Pa/m, ks ", j.shear_stiffness, " Pa/m)")
             .c_str());
  return 1;
}

}  // namespace

void register_materials(lua_State* L) {
  static const Method model_methods[] = {
      {"rock", guarded<m_rock>, "m:rock{...} → RockMaterial", kRockOptions},
      {"joint", guarded<m_joint>,
       "m:joint{...} → JointMaterial\nA joint material: Mohr-Coulomb strength and, when given, the joint's own "
       "stiffness (docs/time_integration.md, \"Joints with their own stiffness\").",
       kJointOptions},
      {"default_joint", guarded<m_default_joint>,
       "m:default_joint() → JointMaterial\nJoint material 0, which edges get when none is given (φ = 30°, "
       "c = 0, σt = 0 unless changed)."},
      {}};
  add_model_methods(L, model_methods, "Materials");
  static const Method no_methods[] = {{}};
  static const luaL_Reg rock_meta[] = {
      {"__newindex", guarded<rock_newindex>}, {"__eq", material_eq}, {"__tostring", rock_tostring}, {nullptr, nullptr}};
  define_type(L, kRockType, no_methods, rock_meta, guarded<rock_index>, kRockFieldNames);
  static const luaL_Reg joint_meta[] = {{"__newindex", guarded<joint_newindex>},
                                        {"__eq", material_eq},
                                        {"__tostring", joint_tostring},
                                        {nullptr, nullptr}};
  define_type(L, kJointType, no_methods, joint_meta, guarded<joint_index>, kJointFieldNames);
}

}  // namespace dda::script
