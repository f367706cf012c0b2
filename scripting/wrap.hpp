// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Shared pieces of the Lua wrappers (one wrap_*.cpp per exposed type).
//
// Every object a script holds is a userdata:
//  - dda.Model: owns a ScriptModel (deleted by __gc).
//  - every other type (Block, BlockSet, EdgeSet, materials, monitors, loads,
//    holes) is a Handle: the model pointer, an id and, for sets, an array of
//    ids inline. Its first user value is the Model userdata, which keeps the
//    model alive while the handle exists. Each use checks the handle is still
//    valid ("attempt to use a removed/invalid block") and belongs to the model
//    it is used with.
#include <lua.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lua_support.hpp"
#include "model.hpp"

namespace dda::script {

inline constexpr const char* kModelType = "dda.Model";
inline constexpr const char* kBlockType = "dda.Block";
inline constexpr const char* kBlockSetType = "dda.BlockSet";
inline constexpr const char* kEdgeSetType = "dda.EdgeSet";
inline constexpr const char* kRockType = "dda.RockMaterial";
inline constexpr const char* kJointType = "dda.JointMaterial";
inline constexpr const char* kMonitorType = "dda.Monitor";
inline constexpr const char* kPointLoadType = "dda.PointLoad";
inline constexpr const char* kPressureType = "dda.Pressure";
inline constexpr const char* kHoleType = "dda.Hole";

struct ModelBox {
  ScriptModel* model;
};

struct Handle {
  ScriptModel* model;
  std::int32_t id;     // block, material, monitor, load or hole id (sets: unused)
  std::int32_t count;  // sets: number of items stored after the header
};

// Items stored after the Handle header of a set.
inline BlockId* set_blocks(Handle* h) { return reinterpret_cast<BlockId*>(h + 1); }
inline EdgeRef* set_edges(Handle* h) { return reinterpret_cast<EdgeRef*>(h + 1); }

// ---- type registration -------------------------------------------------------
// A function of the API with its documentation. `doc`: the call and what it
// returns ("{...}" there stands for the names of its options), then, after a
// line break, what it does (Markdown). `options`: the options table it
// takes, read through these same Names (Options), so it accepts exactly
// what is documented; `returns`: the keys of the table it returns. help()
// and the reference (docs/lua_api*.md, api_reference_pages) come from these
// tables, so the two cannot drift. Arrays end with {}.
struct Method {
  const char* name = nullptr;
  lua_CFunction func = nullptr;
  const char* doc = nullptr;
  Names options = {};
  Names returns = {};
};

// Registers `methods` into the table on top of the stack, and their
// documentation under `owner` ("dda", "dda.Model", ...) and, for the model's
// many methods, a `topic` (a heading of the reference: "Geometry").
void set_methods(lua_State* L, const Method* methods, const char* owner, const char* topic = nullptr);
// The documentation of the function at idx (nullptr: not one of the API's).
const Method* find_method(lua_State* L, int idx);

// Creates the metatable `type` (with __name) whose __index is a table of
// `methods` (plus `index_fallback`, called for keys that are not methods, if
// given: the type's `fields`), and the extra metamethods in `meta`. Every
// function must already be wrapped in guarded<>.
void define_type(lua_State* L, const char* type, const Method* methods, const luaL_Reg* meta,
                 lua_CFunction index_fallback = nullptr, Names fields = {});
// Adds methods to an existing type's method table.
void add_methods(lua_State* L, const char* type, const Method* methods, const char* topic = nullptr);

// What is documented, in the order registered: each owner ("dda", a type)
// with its functions and, for a type, its fields.
struct ApiSection {
  std::string owner;
  std::vector<const Method*> methods;
  std::vector<std::string> topics;  // each method's ("" for none)
  Names fields;
};
std::vector<ApiSection> api_sections(lua_State* L);

// ---- models --------------------------------------------------------------------
ScriptModel& push_new_model(lua_State* L, const Controls& controls);        // pushes a dda.Model
ScriptModel& push_model(lua_State* L, std::unique_ptr<ScriptModel> model);  // pushes it as a dda.Model
// The model at idx (self of a method): must be an open dda.Model.
ScriptModel& check_model(lua_State* L, int idx, std::string_view call);
// Refuses model changes while load histories are evaluated.
void check_not_busy(const ScriptModel& m, std::string_view call);

// ---- handles -------------------------------------------------------------------------
// Pushes a handle of `type` for the model whose userdata is at model_idx.
Handle* push_handle(lua_State* L, int model_idx, const char* type, int id, int extra_bytes = 0);
// The handle at idx, checked for type; `what` names it in messages ("self", "option 'rock'").
Handle* check_handle(lua_State* L, int idx, const char* type, std::string_view call, std::string_view what);
Handle* test_handle(lua_State* L, int idx, const char* type);
// Pushes the dda.Model userdata a handle at idx belongs to.
void push_model_of(lua_State* L, int idx);
// Throws unless the handle's model is open (and, when `model` is given, is that model).
void check_same_model(const Handle* h, const ScriptModel* model, std::string_view call, std::string_view what);

// Blocks.
void push_block(lua_State* L, int model_idx, BlockId b);
// A block handle at idx, valid and in `model` (if given); returns its id.
BlockId check_block(lua_State* L, int idx, const ScriptModel* model, std::string_view call, std::string_view what);
void push_blockset(lua_State* L, int model_idx, std::span<const BlockId> blocks);
std::vector<BlockId> check_blockset(lua_State* L, int idx, const ScriptModel* model, std::string_view call,
                                    std::string_view what);
void push_edgeset(lua_State* L, int model_idx, std::span<const EdgeRef> edges);
std::vector<EdgeRef> check_edgeset(lua_State* L, int idx, const ScriptModel* model, std::string_view call,
                                   std::string_view what);
// An edge set's edges as they stand now (those of a set taken before the
// wave model meshed the blocks: the element edges along them).
std::vector<EdgeRef> edgeset_edges(const Handle* h);
// Materials: a handle or nil (→ def). Returns the id.
int check_rock(lua_State* L, int idx, const ScriptModel* model, std::string_view call, std::string_view what);
int check_joint(lua_State* L, int idx, const ScriptModel* model, std::string_view call, std::string_view what);
void push_rock(lua_State* L, int model_idx, int id);
void push_joint(lua_State* L, int model_idx, int id);
void push_monitor(lua_State* L, int model_idx, int id);
void push_point_load(lua_State* L, int model_idx, int id);
void push_pressure(lua_State* L, int model_idx, int id);
void push_hole(lua_State* L, int model_idx, int id);

// Edge selection shared by m:edges{...} and hole:edges().
struct EdgeQuery {
  std::optional<std::array<double, 4>> on_segment, in_box;
  std::optional<EdgeKind> boundary;  // Domain, Hole; Joint means "any boundary"
  bool any_boundary = false;
  int hole = -1;
  int joint = -1;
  std::optional<BlockId> block;
  double tol = -1;  // < 0: automatic
};
std::vector<EdgeRef> select_edges(const ScriptModel& m, const EdgeQuery& q);

// Controls from an options table (dda.model{...}, m:controls{...}), whose
// names are the controls' (world/controls.hpp).
Options controls_options(lua_State* L, int idx, const char* call);
Names control_option_names();
void parse_controls(const Options& o, Controls& c);

// Pushes a Lua table {x, y}.
void push_point(lua_State* L, const Vec2& p);
// t[key] = value for the table on top of the stack.
void set_number_field(lua_State* L, const char* key, double value);
void set_integer_field(lua_State* L, const char* key, long value);
// Pushes a fresh table with a StepStats.
void push_stats(lua_State* L, const StepStats& s);

// ---- registration of each type (wrap_*.cpp) ----------------------------------------------
void register_model(lua_State* L);
void register_geometry(lua_State* L);  // model geometry methods and dda.Hole
void register_block(lua_State* L);     // dda.Block and dda.BlockSet
void register_edges(lua_State* L);     // dda.EdgeSet
void register_materials(lua_State* L);
void register_monitor(lua_State* L);
void register_loads(lua_State* L);                    // dda.PointLoad and dda.Pressure
void register_boundaries(lua_State* L);               // dda.Boundary, dda.Target (after register_edges)
void register_render(lua_State* L);                   // model render methods, when the renderer is built
void register_render_functions(lua_State* L);         // dda.plot into the module table at the top
void register_ground_motion_functions(lua_State* L);  // dda.ground_motion into the module table at the top
void register_exact_functions(lua_State* L);          // dda.exact_plate_bar, dda.exact_joint_set (likewise)
// The frame sequence `dda run --frames N` asks for, on the new model at model_idx.
void attach_session_frames(lua_State* L, int model_idx);
void register_vtu(lua_State* L);  // m:vtu and dda.Vtu (wrap_vtu.cpp)
// The VTU series `dda run --vtu N` asks for, on the new model at model_idx.
void attach_session_vtu(lua_State* L, int model_idx);

// Adds functions to dda.Model's method table under a topic (a heading of
// the reference), from each wrapper file.
void add_model_methods(lua_State* L, const Method* methods, const char* topic);

}  // namespace dda::script
