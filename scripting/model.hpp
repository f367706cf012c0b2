// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The model a script builds: a dda::World plus what the Lua layer keeps beside
// it: the geometry input for block cutting, which block edges lie on the
// domain or hole boundaries, time-varying loads, and monitors with their CSV
// files. Lua-free except that time histories are evaluated on the calling
// lua_State (once per step, before World::step, never inside parallel work).
#include <lua.hpp>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/cutting.hpp"
#include "lua_support.hpp"
#include "world/checkpoint.hpp"
#include "world/cut_blocks.hpp"
#include "world/world.hpp"

#include "core/output_file.hpp"
#include "run_control.hpp"
namespace dda::script {

class BackgroundRun;

// ---- Monitors -------------------------------------------------------------
// Point fields, then the energy budget's terms since the first step (the
// model's, whatever the point: "energy_kinetic" ... "energy_residual", in
// kEnergyTerms' order from EnergyFirst).
enum class Field : std::uint8_t { Sxx, Syy, Txy, Vx, Vy, Ux, Uy, X, Y, EnergyFirst };
const char* field_name(Field f);
std::optional<Field> parse_field(std::string_view name);
std::string field_list();  // "sxx, syy, txy, vx, vy, ux, uy, x, y, energy_kinetic, ..."
Names field_names();       // each with what it is

struct Monitor {
  std::string name;
  std::filesystem::path path;  // CSV file
  std::vector<Field> fields;
  Vec2 point;        // where it was placed
  int tracked = -1;  // World tracked point
  int every = 1;     // record every N steps
  bool started = false;
  std::vector<long> steps;
  std::vector<double> times;
  std::vector<std::vector<double>> values;  // values[field][row]
  AppendFile file;                          // the CSV, one whole row per record (not open: in memory only)
  std::string write_error;                  // once a row could not be written: every later record raises it again
  // dda run --restart: the rows the CSV file held before this run (header
  // first), put back up to the checkpoint's step when the model restarts.
  std::vector<std::string> previous_lines;

  // Closes the CSV; throws dda::Error if the system reports a failure.
  void close();
};

// A monitor's record in a checkpoint: what it recorded so far.
struct SavedMonitor {
  std::string name;
  std::vector<long> steps;
  std::vector<double> times;
  std::vector<std::vector<double>> values;
  template <class Archive>
  void fields(Archive& ar) {
    ar(name, steps, times, values);
  }
};

// ---- Loads ----------------------------------------------------------------
// The force of a point load: (fx, fy) histories or a function returning both,
// evaluated here once per step before the step at its planned end time; or a
// direction times a magnitude history (the paper's FHI), which a constant or
// a {t, value} table hands to the engine (evaluated at each step's end).
struct ForceInput {
  VecTimeInput xy;
  bool along = false;
  Vec2 direction = Vec2::UnitX();  // unit vector when `along`
  TimeInput magnitude;
  bool engine_driven() const { return along && !magnitude.is_function(); }
  bool is_function() const { return along ? magnitude.is_function() : xy.is_function(); }
  bool constant() const { return along ? magnitude.is_constant() : xy.is_constant(); }
  Vec2 at(lua_State* L, double t) const { return along ? Vec2(direction * magnitude.at(L, t)) : xy.at(L, t); }
  bool is_lost_function() const { return along ? magnitude.is_lost_function() : xy.is_lost_function(); }
  template <class Archive>
  void fields(Archive& ar) {
    ar(xy, along, direction, magnitude);
  }
};

struct ScriptPointLoad {
  int world_id = -1;
  BlockId block = -1;
  Vec2 point;
  ForceInput force;
  bool engine_history = false;  // the World holds a history for it (all later values go through one)
  Vec2 current = Vec2::Zero();  // last value set from here
  template <class Archive>
  void fields(Archive& ar) {
    ar(world_id, block, point, force, engine_history, current);
  }
};

// Prescribed displacements (the paper's DHI): engine targets at material
// points, all driven by one input.
struct ScriptTarget {
  enum class Mode { Vector, Displacement, Velocity, Acceleration };
  friend constexpr Mode enum_last(Mode) { return Mode::Acceleration; }  // (core/archive.hpp)
  std::vector<int> world_ids;
  bool on_edges = false;  // made on edges (World::add_edge_targets): its ids follow a meshing
  Mode mode = Mode::Vector;
  Vec2 vector = Vec2::Zero();  // Mode::Vector
  TimeInput input;             // magnitude along each point's direction (a table, or a function for Displacement)
  double current = 0;          // last value of a function input
  template <class Archive>
  void fields(Archive& ar) {
    ar(world_ids, mode, vector, input, current);
  }
};

// A pressure on a set of edges (the engine's SHI load: normal to each edge,
// integrated along it, pushing into the block when positive). A constant or a
// {t, p} table goes to the engine as a history (evaluated at each step's end,
// t + Δt); a Lua function is evaluated here once per step, before the step.
struct ScriptPressure {
  std::vector<EdgeRef> edges;
  int world_id = -1;
  TimeInput pressure;
  double current = 0;  // last value of a function input
  template <class Archive>
  void fields(Archive& ar) {
    ar(edges, world_id, pressure, current);
  }
};

// Something that follows the run step by step (the renderer's frame
// sequences). Called on the Lua thread, between steps, never inside one.
struct StepHook {
  virtual ~StepHook() = default;
  virtual void before_step(const World&) {}
  virtual void after_step(const World&) {}  // after the monitors have recorded the step
  virtual void monitor_added(int /*tracked_point*/, const std::string& /*name*/) {}
  // dda run --restart: the World now holds the checkpoint's state.
  virtual void restarted(const World&) {}
};

struct Totals {
  long steps = 0;
  long step_cuts = 0;
  long open_close_iterations = 0;
  long cg_iterations = 0;
  long patch_iterations = 0;
  double wall_seconds = 0;
  template <class Archive>
  void fields(Archive& ar) {
    ar(steps, step_cuts, open_close_iterations, cg_iterations, patch_iterations, wall_seconds);
  }
};

class ScriptModel {
 public:
  explicit ScriptModel(const Controls& controls);
  explicit ScriptModel(World world);
  ~ScriptModel();

  World& world() { return *world_; }
  const World& world() const { return *world_; }
  bool closed() const { return !world_; }
  // Releases the World and everything attached (m:close()).
  void close();

  // ---- geometry input (cutting) -------------------------------------------
  geometry::CutInput& cut_input() { return cut_; }
  bool has_domain() const { return has_domain_; }
  // `joint`: the joint material of the boundary's edges (what an explicit
  // block touching them slides on).
  void set_domain(std::vector<Vec2> polygon, int rock, int joint);
  int add_hole(std::vector<Vec2> polygon, int joint);  // 0-based hole index
  int hole_count() const { return static_cast<int>(cut_.holes.size()); }
  bool generated() const { return generated_; }
  // Cuts the domain and adds every block to the World (add_cut_blocks).
  // Returns the new ids.
  std::vector<BlockId> generate();
  const geometry::CutStats& cut_stats() const { return cut_stats_; }

  // An explicit block; edge_joints as World::add_block.
  BlockId add_block(std::vector<Vec2> vertices, int rock, std::vector<int> edge_joints) {
    return world_->add_block(std::move(vertices), rock, std::move(edge_joints));
  }
  const EdgeTag& edge_tag(EdgeRef e) const { return world_->block_edge_tag(e.block, e.edge); }

  // ---- queries on the current geometry ------------------------------------
  std::optional<BlockId> block_at(const Vec2& p) const;
  int edge_count(BlockId b) const { return static_cast<int>(world_->block_vertices(b).size()); }
  std::pair<Vec2, Vec2> edge_points(EdgeRef e) const;
  // Size of the model (bounding-box diagonal), for default tolerances.
  double extent() const;

  // ---- loads, constraints, monitors -------------------------------------------
  int add_point_load(BlockId b, const Vec2& point, ForceInput force, lua_State* L);
  void set_point_load(int id, ForceInput force, lua_State* L);
  ScriptPointLoad& point_load(int id) { return loads_.at(id); }
  Vec2 point_load_value(int id, lua_State* L) const;  // the force of the last step
  int point_load_count() const { return static_cast<int>(loads_.size()); }
  int add_pressure(std::vector<EdgeRef> edges, TimeInput p, lua_State* L);
  void set_pressure(int id, TimeInput p, lua_State* L);
  ScriptPressure& pressure(int id) { return pressures_.at(id); }
  // The pressure applied in the last step (at its end time).
  double pressure_value(int id, lua_State* L) const;
  int pressure_count() const { return static_cast<int>(pressures_.size()); }
  int add_fixed_point(BlockId b, const Vec2& p);
  void fix_edges(const std::vector<EdgeRef>& edges) { world_->fix_edges(edges); }

  // Targets at material points; directions empty (Mode::Vector without
  // direction) or one unit vector per point.
  int add_target(const std::vector<std::pair<BlockId, Vec2>>& points, const std::vector<Vec2>& directions,
                 ScriptTarget target, lua_State* L);
  // Targets at the end points of edges (World::add_edge_targets: along
  // `direction`, or the edges' inward normals when it is zero).
  int add_edge_targets(const std::vector<EdgeRef>& edges, const Vec2& direction, ScriptTarget target, lua_State* L);
  void set_target(int id, ScriptTarget input, lua_State* L);
  ScriptTarget& target(int id) { return targets_.at(id); }
  int target_count() const { return static_cast<int>(targets_.size()); }
  int fixed_point_count() const { return fixed_points_; }

  int add_monitor(std::unique_ptr<Monitor> m);
  Monitor& monitor(int id) { return *monitors_.at(id); }
  int monitor_count() const { return static_cast<int>(monitors_.size()); }
  double field_value(const Monitor& m, Field f) const;

  StepHook& add_hook(std::unique_ptr<StepHook> hook);
  std::span<const std::unique_ptr<StepHook>> hooks() const { return hooks_; }

  // ---- stepping -------------------------------------------------------------
  // Before the first step: the wave model (World::decide_wave_model), this
  // model's Lua functions sampled every Δt over [0, window] (s: the run's
  // end when the call that steps says it; at least 1000 steps) and read as
  // the engine reads its histories;
  // where it meshed the blocks, the loads and targets held here follow.
  // Returns what was decided (notes, warnings).
  const WaveModel& decide_wave_model(lua_State* L, double window);
  // One step: evaluate the time-varying loads at the step's planned end time
  // (on L, serially), World::step(), record the monitors. L is used only
  // for loads that are Lua functions (loads_call_lua()).
  StepStats step(lua_State* L);
  // One settling step (world/settle.hpp: static, the time held; the World's
  // settling() guard must be held): the loads at the held time, no monitor
  // records (settling is not part of the run's history).
  StepStats settle_step(lua_State* L);
  bool loads_call_lua() const;
  // dda run --threads N: the thread count every step uses, whatever the
  // script sets (−1: the controls').
  int threads_override = -1;
  // The time at which the next step's loads are evaluated.
  double load_time() const;
  const Totals& totals() const { return totals_; }
  // True while load histories are being evaluated (the model must not be changed then).
  bool busy() const { return busy_; }

  bool controls_logged = false;  // the run log has this model's controls

  // ---- runs (run_control.hpp) ------------------------------------------------
  // Who may touch the model now, and the run in progress; shared with the
  // live view, which may outlive the model.
  RunControl& control() { return *control_; }
  const std::shared_ptr<RunControl>& shared_control() const { return control_; }
  // The run going on in the background (m:start), or its end not yet
  // collected; null otherwise.
  std::unique_ptr<BackgroundRun> background;

  // ---- checkpoints (world/checkpoint.hpp) -------------------------------------
  // Its number in the run: 1 for the first model made (dda.model or
  // dda.load), 2 for the next...: the model a --restart continues.
  int number = 0;
  // m:save: the World, and beside it the loads' inputs (a Lua function as
  // the last value it gave: a checkpoint cannot hold Lua code) and what the
  // monitors recorded.
  void save(const std::filesystem::path& path) const;
  // dda.load: the model of a checkpoint; an input that was a Lua function
  // keeps its last value (one warning each in `warnings`).
  static std::unique_ptr<ScriptModel> load(const std::filesystem::path& path, std::vector<std::string>& warnings);
  // The same from a checkpoint's contents (`what` names it in messages).
  static std::unique_ptr<ScriptModel> from_checkpoint(Checkpoint c, const std::string& what,
                                                      std::vector<std::string>& warnings);
  // dda run --restart: this model, built again by the script, takes the
  // state of `saved` (its loads keep the script's inputs; monitors take the
  // saved records, their files keep their rows up to the checkpoint). Throws
  // dda::Error, naming `what`, when
  // the script built another model.
  void restore(ScriptModel& saved, const std::string& what);
  // After a restore: the step count the straight run had where the script
  // now stands (stepping calls that end before the checkpoint return at
  // once); empty once caught up or unknown (wrap_model.cpp, run_loop).
  std::optional<long> replay_mark;
  double last_checkpoint_time = 0;  // --checkpoint-every T s: the time of the last one

 private:
  // World::step() with the totals kept.
  StepStats counted_step();
  void apply_loads(lua_State* L, double t);
  void record(Monitor& m);
  void hand_over(ScriptPressure& p, lua_State* L);
  void hand_over(ScriptPointLoad& load, lua_State* L);
  void hand_over(ScriptTarget& t, lua_State* L);
  void push_force(ScriptPointLoad& load, const Vec2& f);
  template <class Archive>
  void script_fields(Archive& ar, std::vector<SavedMonitor>& monitors);
  // Read from a checkpoint: every load, target and edge against the World
  // read with it, each monitor's records of equal length, text printable.
  void check_loaded(const LoadCheck& check);

  std::unique_ptr<World> world_;
  geometry::CutInput cut_;
  bool has_domain_ = false;
  bool generated_ = false;
  BoundaryJoints boundary_joints_;
  geometry::CutStats cut_stats_;
  std::vector<ScriptPointLoad> loads_;
  std::vector<ScriptPressure> pressures_;
  std::vector<ScriptTarget> targets_;
  std::vector<std::unique_ptr<Monitor>> monitors_;
  std::vector<std::unique_ptr<StepHook>> hooks_;
  int fixed_points_ = 0;
  std::vector<SavedMonitor> saved_monitors_;  // of a model read from a checkpoint
  Totals totals_;
  bool busy_ = false;
  std::shared_ptr<RunControl> control_;
};

}  // namespace dda::script
