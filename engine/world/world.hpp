#pragma once
// The model and its time step. A World owns every block, material, load,
// constraint and contact; `step()` advances it by one DDA time step:
//
//   DetectContacts → loop { Assemble → Solve → CheckContacts } until settled
//   → ControlStep (cut Δt and redo if needed) → Update
//
// Everything is referred to by integer id. Nothing here knows Lua or OpenGL.
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "contact/contact.hpp"
#include "core/material.hpp"
#include "core/types.hpp"
#include "solver/block_sparse_matrix.hpp"

namespace dda {

struct Controls {
  PlaneMode plane = PlaneMode::Stress;
  double g0 = 0;             // normal contact spring (N/m per unit thickness); 0 → 50 × largest E
  double shear_ratio = 0.4;  // shear spring = shear_ratio × g0 (Shi's 2/5)
  double g1 = 0;             // upper step time (s); 0 → estimate from Eqs. 1–3 (suggested_time_step)
  double g2 = 0.005;         // largest step displacement / half the model height
  double gg = 1;             // dynamic parameter: share of velocity carried into the next step
  int open_close_limit = 6;  // open-close iterations before Δt is cut and the step redone
  double fixed_point_factor = 100;  // fixed-point spring = factor × g0
  Vec2 gravity = Vec2::Zero();      // m/s²
  double cut_factor = 1.0 / 3.0;    // Δt multiplier when a step is redone
  int max_step_cuts = 20;           // cuts in one step before giving up (error)
  double cg_tolerance = 1e-10;      // PCG relative residual
  int cg_max_iterations = 0;        // 0 → 10 × unknowns + 100
  int threads = 0;                  // 0 → every core
};

// Stage times (seconds) and counts of one step, including redone attempts.
struct StepStats {
  double dt = 0;
  int open_close_iterations = 0;
  int cg_iterations = 0;
  int step_cuts = 0;
  int contacts = 0;
  int closed_contacts = 0;
  double max_displacement_ratio = 0;  // largest vertex displacement / (g2 bound)
  double t_detect = 0, t_assemble = 0, t_solve = 0, t_check = 0, t_update = 0, t_total = 0;
};

class World {
 public:
  World();
  explicit World(const Controls& controls);
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  // Controls may be changed between steps; they are validated at the next step.
  Controls& controls() { return controls_; }
  const Controls& controls() const { return controls_; }

  // ---- Model building -------------------------------------------------------
  int add_rock_material(const RockMaterial& m);
  // Joint material 0 exists from the start ({30°, 0, 0}); edges default to it.
  int add_joint_material(const JointMaterial& m);
  RockMaterial& rock_material(int id);
  JointMaterial& joint_material(int id);
  int rock_material_count() const { return static_cast<int>(rocks_.size()); }
  int joint_material_count() const { return static_cast<int>(joints_.size()); }

  // A block from a simple polygon (either orientation; stored counter-clockwise).
  // edge_joints[k] is the joint material of the edge from vertex k to k+1 of the
  // polygon as given (empty → all 0). Throws dda::Error for a degenerate polygon
  // or an unknown material.
  BlockId add_block(std::vector<Vec2> vertices, int rock_material, std::vector<int> edge_joints = {});

  // Initial conditions.
  void set_block_velocity(BlockId b, const Vec6& velocity);
  void set_block_stress(BlockId b, const Vec3& stress);

  // A point load fixed to the material point `point` of block b.
  int add_point_load(BlockId b, const Vec2& point, const Vec2& force);
  void set_point_load(int id, const Vec2& force);
  // A fixed point: a stiff spring (fixed_point_factor × g0) that pulls the
  // material point back to where it started, residual included.
  int add_fixed_point(BlockId b, const Vec2& point);
  // A material point followed through the run (for monitors).
  int add_tracked_point(BlockId b, const Vec2& point);
  Vec2 tracked_position(int id) const;
  Vec2 tracked_displacement(int id) const;
  BlockId tracked_block(int id) const;

  // ---- Stepping -------------------------------------------------------------
  StepStats step();
  // Δt from the paper's Eqs. 1–3 with a = 0.05 and b = 0.177:
  // min(a·h_min/C_P, 2b·sqrt(m_min/g0)).
  double suggested_time_step() const;

  // ---- Read access ----------------------------------------------------------
  double time() const { return time_; }
  long step_count() const { return steps_; }
  double current_dt() const { return dt_; }
  const StepStats& last_stats() const { return last_stats_; }

  std::size_t block_count() const { return vertex_start_.empty() ? 0 : vertex_start_.size() - 1; }
  std::span<const Vec2> block_vertices(BlockId b) const;
  int block_edge_joint(BlockId b, int edge) const;
  Vec2 block_centroid(BlockId b) const { return centroid_[check(b)]; }
  double block_area(BlockId b) const { return area_[check(b)]; }
  double block_mass(BlockId b) const { return mass_[check(b)]; }
  int block_material(BlockId b) const { return material_[check(b)]; }
  Vec3 block_stress(BlockId b) const { return stress_[check(b)]; }  // (σxx, σyy, τxy), tension +
  Vec6 block_velocity(BlockId b) const { return velocity_[check(b)]; }  // rates of (u0,v0,r0,εx,εy,γxy)
  Vec2 velocity_at(BlockId b, const Vec2& p) const;
  // Displacement of the block's centroid since the start (or since it was added).
  Vec2 block_displacement(BlockId b) const { return centroid_[check(b)] - initial_centroid_[check(b)]; }
  const std::vector<Contact>& contacts() const { return contacts_; }

  // Half the model's height at the start (y extent / 2): the g2 reference length.
  double half_height() const;

  // The linear system of the last open-close iteration (A·D = F), for tests
  // and debugging.
  const BlockSparseMatrix& last_matrix() const;
  const VecX& last_rhs() const;

  // Hash of the full state (positions, velocities, stresses, contacts), for
  // determinism checks.
  std::uint64_t state_hash() const;

 private:
  struct Impl;
  BlockId check(BlockId b) const;

  // The stages of step(), in order (world/step.cpp).
  void prepare_first_step();      // validate the model once: materials, overlaps, g2 length
  void resolve_controls();        // validate controls, fill in automatic g0 and g1
  void detect_contacts();         // broad + narrow phase, carry states, linearise, matrix shape
  int solve_step(double dt);      // loop { assemble, solve, check contacts }; 0 or a rejection
  void assemble_block_terms(double dt);  // elastic, inertia, stress, loads, fixed points
  void assemble_contacts();       // block terms + contact springs and friction into the matrix
  bool check_contacts();          // open-close decision; true when a contact changed
  double largest_step_displacement() const;
  double deepest_penetration() const;
  void update(double dt);         // move vertices, stresses, velocities, contacts; advance time

  Controls controls_;
  std::vector<RockMaterial> rocks_;
  std::vector<JointMaterial> joints_;

  // Hot per-block state (solver arrays, indexed by block id).
  std::vector<int> vertex_start_;  // block b owns vertices_[vertex_start_[b] .. vertex_start_[b+1])
  std::vector<Vec2> vertices_;
  std::vector<int> edge_joint_;    // parallel to vertices_: joint of edge k → k+1
  std::vector<Vec2> centroid_, initial_centroid_;
  std::vector<double> area_, sxx_, syy_, sxy_, mass_;
  std::vector<int> material_;
  std::vector<Vec3> stress_;
  std::vector<Vec6> velocity_;
  std::vector<Vec6> last_displacement_;  // previous step's solution: the PCG warm start

  // Loads and constraints attached to material points.
  struct PointLoad { BlockId block; Vec2 point; Vec2 force; };
  struct FixedPoint { BlockId block; Vec2 point; Vec2 origin; };
  struct TrackedPoint { BlockId block; Vec2 point; Vec2 origin; };
  std::vector<PointLoad> point_loads_;
  std::vector<FixedPoint> fixed_points_;
  std::vector<TrackedPoint> tracked_;

  std::vector<Contact> contacts_;

  double time_ = 0;
  long steps_ = 0;
  double dt_ = 0;
  double half_height_ = 0;
  bool prepared_ = false;
  StepStats last_stats_;
  std::unique_ptr<Impl> impl_;  // scratch buffers reused from step to step
};

}  // namespace dda
