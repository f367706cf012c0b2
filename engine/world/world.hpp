// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The model: a World owns every block, material, load, boundary, followed
// point and contact (WorldState), and a Stepper that advances it one DDA
// time step at a time (stepper.cpp opens with the step as its table of
// contents). Everything is referred to by integer id. Nothing here knows Lua
// or OpenGL.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "solver/block_sparse_matrix.hpp"
#include "world/settle.hpp"
#include "world/time_step_rule.hpp"
#include "world/world_state.hpp"

namespace dda {

class Stepper;
class ContactModel;

class World {
 public:
  World();
  explicit World(const Controls& controls);
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  // Controls may be changed between steps; they are validated at the next step.
  Controls& controls() { return s_.controls; }
  const Controls& controls() const { return s_.controls; }

  // ---- Model building -------------------------------------------------------
  int add_rock_material(const RockMaterial& m);
  // Joint material 0 exists from the start ({30°, 0, 0}); edges default to it.
  int add_joint_material(const JointMaterial& m);
  RockMaterial& rock_material(int id);
  JointMaterial& joint_material(int id);
  const JointMaterial& joint_material(int id) const;
  int rock_material_count() const { return static_cast<int>(s_.rocks.size()); }
  int joint_material_count() const { return static_cast<int>(s_.joints.size()); }

  // A block from a simple polygon (either orientation; stored counter-clockwise).
  // edge_joints[k] is the joint material of the edge from vertex k to k+1 of the
  // polygon as given (empty → all 0), edge_tags[k] what that edge was made
  // from (empty → all EdgeKind::Free). Throws dda::Error for a degenerate
  // polygon or an unknown material. (Blocks cut from a domain: add_cut_blocks.)
  // A block whose rock material (or, failing that, the controls) has a mesh
  // size is meshed (block/mesh.hpp): its elements are added as blocks, and
  // the first element's id is returned.
  BlockId add_block(std::vector<Vec2> vertices, int rock_material, std::vector<int> edge_joints = {},
                    std::vector<EdgeTag> edge_tags = {});

  // Initial conditions. On an element of a meshed block they set the whole
  // block (the velocity's rates about the block's centroid).
  void set_block_velocity(BlockId b, const Vec6& velocity);
  void set_block_stress(BlockId b, const Vec3& stress);

  // A point load fixed to the material point `point` of block b.
  int add_point_load(BlockId b, const Vec2& point, const Vec2& force);
  void set_point_load(int id, const Vec2& force);  // also drops a force history (below)
  // A fixed point: a stiff spring (fixed_point_factor × g0) that pulls the
  // material point back to where it started, residual included.
  int add_fixed_point(BlockId b, const Vec2& point);
  // A material point followed through the run (for monitors).
  int add_tracked_point(BlockId b, const Vec2& point);
  Vec2 tracked_position(int id) const;
  Vec2 tracked_displacement(int id) const;
  BlockId tracked_block(int id) const;

  // ---- Loads and boundaries on edges (the paper's SHI, FHI, DHI, VBC, SBC) ---
  // SHI: a pressure (Pa) on edges, normal to each edge and pushing into its
  // block, integrated exactly along the edge (its current length and normal).
  int add_pressure_load(const std::vector<EdgeRef>& edges, double pressure = 0);
  void set_pressure(int id, double pressure);
  void set_pressure_history(int id, History pressure);
  // FHI: the point load's force becomes direction × magnitude(t).
  void set_point_load_history(int id, const Vec2& direction, History magnitude);
  // DHI: a stiff spring (fixed_point_factor × g0) pulls the material point to
  // start + target. With a direction (normalised) it acts along it only and
  // the target is a magnitude along it; with a zero direction it acts in both.
  int add_displacement_target(BlockId b, const Vec2& point, const Vec2& direction = Vec2::Zero());
  void set_target_displacement(int id, const Vec2& target);    // along a direction: target.x() is the magnitude
  void set_target_history(int id, History displacement);       // magnitude along the direction
  void set_target_velocity_history(int id, History velocity);  // integrated to displacement
  // Integrated twice from rest (a rigid shaken base driven by a ground
  // acceleration; exact for the piecewise-linear history).
  void set_target_acceleration_history(int id, History acceleration);
  Vec2 target_point_displacement(int id) const;  // the material point's displacement so far
  Vec2 target_value(int id) const;               // the last target applied (vector)
  std::size_t point_load_count() const { return s_.loads.point_load_count(); }
  std::size_t pressure_count() const { return s_.loads.pressure_count(); }
  std::size_t target_count() const { return s_.boundaries.target_count(); }
  std::size_t fixed_point_count() const { return s_.boundaries.fixed_point_count(); }

  // Fixed boundary: fixed points at both ends of each edge.
  void fix_edges(const std::vector<EdgeRef>& edges);
  // VBC (Eqs. 6–12): at each end of each edge, a dashpot pair over half the
  // edge length: traction −ρ(C_P v_n n + C_S v_s s), n the outward normal,
  // with ρ, C_P = sqrt((K + 4G/3)/ρ), C_S = sqrt(G/ρ) of the edge's block.
  // With a rock material `medium` (≥ 0) ρ, C_P, C_S are that material's: the
  // half-space beyond a compliant base.
  int add_viscous_boundary(const std::vector<EdgeRef>& edges, int medium = -1);
  // A compliant (quiet) base: the viscous boundary also brings in a wave of
  // particle velocity (vx(t), vy(t)) from outside, traction 2ρC·v_in
  // (vertically incident S: vx on a horizontal base; P: vy). See
  // docs/seismic.md.
  void set_incident_velocity(int boundary, History vx, History vy);
  // Free-field side (boundary/free_field.hpp): a vertical side of the model
  // coupled through dashpots and the column's stresses to a 1-D column beside
  // it, driven by the compliant base `base`'s incident wave. One call per
  // side; the column takes the plane mode of the controls now.
  int add_free_field(const std::vector<EdgeRef>& side, int base);
  Vec2 free_field_velocity(int boundary, double y) const;  // the column's, at the node nearest y
  // SBC (Eq. 22): at each end of each edge a spring p·l·TᵀT (Eq. 21's p
  // without the edge length when per_length is false). As the paper says, it
  // is the fixed-point sub-matrix without the fixed point's residual term: it
  // resists each step's displacement Δu with p·l·Δu and does not pull the
  // boundary back to its start (acting like a dashpot p·l·Δt).
  int add_spring_boundary(const std::vector<EdgeRef>& edges, double p, bool per_length = true);
  // Forces (N) the boundary's points exerted at the end of the last step.
  std::vector<Vec2> boundary_point_forces(int id) const;
  Vec2 boundary_force(int id) const;

  // ---- Stepping -------------------------------------------------------------
  // The wave model (world/wave_model.hpp), decided once, before the first
  // step: the highest frequency of the dynamic loads (with the inputs the
  // engine does not hold, sampled by the caller: a script's functions), and,
  // where the controls leave it to the engine and a block is larger than
  // the element that resolves it, every such block meshed in place (ids
  // kept: block b becomes the first element of its mesh; loads, boundaries
  // and followed points move onto the elements). step() decides it without
  // such inputs when no one did before.
  const WaveModel& decide_wave_model(std::span<const LoadSignal> script_signals = {});
  const WaveModel& wave_model() const { return s_.wave; }
  // The integrator and the elements' mass the steps use (the controls', or
  // what "auto" resolves to: world/wave_model.hpp).
  Integrator integrator_in_use() const { return effective_integrator(s_); }
  MeshMass mesh_mass_in_use() const { return effective_mesh_mass(s_); }
  // The edges that now stand where edge `e` of the blocks before the wave
  // model's meshing stood ({e} when nothing was meshed).
  std::vector<EdgeRef> edges_since_meshing(EdgeRef e) const;
  // Increases when the wave model meshes the blocks (edges taken before are
  // then mapped with edges_since_meshing).
  int mesh_generation() const { return s_.wave.meshed_blocks > 0 ? 1 : 0; }
  // The displacement targets made together on edges with target `id`.
  std::vector<int> edge_target_ids(int id) const { return s_.boundaries.edge_target_ids(id); }
  // Targets at the end points of edges (Boundaries::add_edge_targets):
  // directed along `direction`, or the edges' inward normals when it is
  // zero; not directed, in both components.
  std::vector<int> add_edge_targets(const std::vector<EdgeRef>& edges, bool directed,
                                    const Vec2& direction = Vec2::Zero());
  const std::vector<EdgeRef>& pressure_edges(int id) const { return s_.loads.pressure_edges(id); }
  BlockId point_load_block(int id) const { return s_.loads.point_load_block(id); }

  // One DDA time step (world/stepper.cpp: the step as its table of contents).
  StepStats step();
  // The upper step time g1 = 0 stands for, and why (world/time_step_rule.hpp).
  TimeStepChoice default_time_step() const { return dda::default_time_step(s_); }

  // Settling (world/settle.hpp): while the returned guard lives, step()
  // takes settling steps (static, the time held); unbalanced_force() is the
  // convergence measure after each; come_to_rest() ends settling.
  std::unique_ptr<SettlingSteps> settling() { return std::make_unique<SettlingSteps>(s_); }
  UnbalancedForce unbalanced_force() const { return dda::unbalanced_force(s_); }
  void come_to_rest() { dda::come_to_rest(s_); }
  bool settling() const { return s_.hold_time; }

  // ---- Read access ----------------------------------------------------------
  double time() const { return s_.time; }
  long step_count() const { return s_.steps; }
  double current_dt() const { return s_.dt; }
  const StepStats& last_stats() const { return s_.last_stats; }

  std::size_t block_count() const { return s_.blocks.count(); }
  std::span<const Vec2> block_vertices(BlockId b) const;
  std::span<const Vec2> block_initial_vertices(BlockId b) const;  // as added (counter-clockwise)
  int block_edge_joint(BlockId b, int edge) const;
  const EdgeTag& block_edge_tag(BlockId b, int edge) const;
  Vec2 block_centroid(BlockId b) const { return s_.blocks.centroid[check(b)]; }
  double block_area(BlockId b) const { return s_.blocks.area[check(b)]; }
  double block_mass(BlockId b) const { return s_.blocks.mass[check(b)]; }
  int block_material(BlockId b) const { return s_.blocks.material[check(b)]; }
  Vec3 block_stress(BlockId b) const { return s_.blocks.stress[check(b)]; }      // (σxx, σyy, τxy), tension +
  Vec6 block_velocity(BlockId b) const { return s_.blocks.velocity[check(b)]; }  // rates of (u0,v0,r0,εx,εy,γxy)
  Vec2 velocity_at(BlockId b, const Vec2& p) const;
  // Displacement of the block's centroid since the start (or since it was added).
  Vec2 block_displacement(BlockId b) const {
    return s_.blocks.centroid[check(b)] - s_.blocks.initial_centroid[check(b)];
  }
  const std::vector<Contact>& contacts() const { return s_.contacts; }
  // The energy budget (world/energy_budget.hpp): held now, work since the
  // first step and in the last one.
  const EnergyBudget& energy() const { return s_.energy; }

  // Half the model's height at the start (y extent / 2): the g2 reference length.
  double half_height() const;

  // The linear system of the last open-close iteration (A·D = F), for tests
  // and debugging.
  const BlockSparseMatrix& last_matrix() const;
  const VecX& last_rhs() const;
  // The contact law of the last step, with its per-contact history
  // (contact/contact_model.hpp; nullptr before the first step), for tests.
  const ContactModel* contact_model() const;

  // Hash of the full state (positions, velocities, stresses, contacts), for
  // determinism checks.
  std::uint64_t state_hash() const;

  // Checkpoints (world/checkpoint.hpp): the whole state, the Stepper's
  // included (core/archive.hpp).
  template <class Archive>
  void fields(Archive& ar);

 private:
  BlockId check(BlockId b) const;
  BlockId append_block(const std::vector<Vec2>& vertices, int rock_material, const std::vector<int>& edge_joints,
                       const std::vector<EdgeTag>& edge_tags);
  BlockId add_meshed_block(const std::vector<Vec2>& outline, int rock_material, const std::vector<int>& edge_joints,
                           const std::vector<EdgeTag>& edge_tags, double mesh_size, const std::string& what);

  WorldState s_;
  std::unique_ptr<Stepper> stepper_;  // scratch reused from step to step
};

}  // namespace dda
