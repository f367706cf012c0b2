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
#include "loading/history.hpp"
#include "solver/block_sparse_matrix.hpp"
#include "solver/solver_settings.hpp"

namespace dda {

struct Controls {
  PlaneMode plane = PlaneMode::Stress;
  double g0 = 0;             // normal contact spring (N/m per unit thickness); 0 → 50 × largest E
  double shear_ratio = 0.4;  // shear spring = shear_ratio × g0 (Shi's 2/5)
  double g1 = 0;             // upper step time (s); 0 → estimate from Eqs. 1–3 (suggested_time_step)
  double g2 = 0.005;         // largest step displacement / half the model height
  double gg = 1;             // dynamic parameter: share of velocity carried into the next step
  int open_close_limit = 6;  // open-close iterations before Δt is cut and the step redone
  // Open-close hysteresis, as a fraction of half the model height: a closed
  // contact opens once separated by more than this, an open one closes once
  // penetrated by more; a locked contact slides once its shear force exceeds
  // its strength by the shear spring times this. Without it, contacts that
  // carry next to no force (the Poisson-loaded vertical joints of a wall)
  // flip state on round-off and the iteration never settles.
  double contact_tolerance = 1e-9;
  // Contact range (m): pairs closer than this at the start of a step are
  // contacts; a step in which a vertex moves more than range / 2.5 is cut.
  // 0 → automatic: starts at a tenth of the median edge length (fine models
  // then do not carry their blocks' second neighbours as contacts: wave
  // problems move micrometres a step) and widens, redoing the step, whenever
  // a vertex moves further, up to Shi's 2.5·g2·(half height).
  double contact_range = 0;
  double fixed_point_factor = 100;  // fixed-point spring = factor × g0
  Vec2 gravity = Vec2::Zero();      // m/s²
  double cut_factor = 1.0 / 3.0;    // Δt multiplier when a step is redone
  int max_step_cuts = 20;           // cuts in one step before giving up (error)
  double cg_tolerance = 1e-10;      // PCG relative residual of the accepted solution
  // PCG relative residual while contact states still change, in steps after
  // one whose solves took over 30 iterations (the final solve of a step is
  // always tightened to the accepted tolerance: cg_tolerance, or in static
  // analysis cg_static_tolerance); = cg_tolerance: off.
  double cg_open_close_tolerance = 1e-4;
  // PCG relative residual of the accepted solution in static analysis (gg = 0:
  // no velocity carried into the next step) in steps after long solves (over
  // 30 CG iterations per solve: walls); the larger of it and cg_tolerance
  // applies. Such a step's friction already carries the error of its loose
  // open-close solves (the normal force of a solve good to
  // cg_open_close_tolerance), and with gg = 0 a displacement error is not
  // carried on as a velocity, so solving the last pass past 1e-6 changes the
  // answer less than the loose solves do: wall(20) over 300 steps, 1e-6 and
  // 1e-10 agree to 1.7e-11 m and both end 7.5e-8 m (of 8.4e-4 m settled)
  // from the scheme's limit (every solve at 1e-12 or tighter), and wall(40)
  // takes 294 against 486 CG iterations per step (40 against 64 ms). Where
  // contacts slide and steps are cut (wall(10), gravity tilted 22°, 200
  // steps), 1e-10, 1e-8 and 1e-6 end 4.7e-6, 1.1e-6 and 1.2e-6 m from the
  // limit (of 3.2e-4 m): there the loose solves decide which contacts change
  // state in which step. Dynamic analysis (gg > 0) keeps cg_tolerance:
  // a wall(6) with gg = 1 moved 3e-5 of its settlement at 1e-6, against
  // 2e-6 at 1e-10. = cg_tolerance: off.
  double cg_static_tolerance = 1e-6;
  // Start each step's open-close iteration from the contact states the warm
  // start predicts (closing and friction transitions only), not from the last
  // step's: fewer iterations in wave problems (blast(2): 2.95 → 2.08 per
  // step; not done after long solves, whose warm start predicts nothing).
  // The answer is another consistent set of states, not the same bits.
  bool predict_states = true;
  // The linear solver's own knobs (solver/solver_settings.hpp): the PCG's
  // preconditioner, block-Jacobi refresh tolerance and re-solve patches.
  SolverSettings solver;
  int cg_max_iterations = 0;  // 0 → 10 × unknowns + 100
  int threads = 0;            // 0 → every core
};

// An edge of a block: from vertex `edge` to `edge + 1` (counter-clockwise).
struct EdgeRef {
  BlockId block = -1;
  int edge = -1;
};

enum class BoundaryKind { Viscous, Spring };

// Stage times (seconds) and counts of one step, including redone attempts.
struct StepStats {
  double dt = 0;
  int open_close_iterations = 0;
  int cg_iterations = 0;     // over all rows
  int patch_iterations = 0;  // confined to the patch of a re-solve (Controls::patch_hops)
  int step_cuts = 0;
  std::string cut_reason;  // why the last cut was made ("" when none), with the block when one is to blame
  int contacts = 0;
  int closed_contacts = 0;
  bool contacts_searched = false;     // a full contact search ran (else the list was reused)
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
  Vec2 target_point_displacement(int id) const;                // the material point's displacement so far
  Vec2 target_value(int id) const;                             // the last target applied (vector)

  // Fixed boundary: fixed points at both ends of each edge.
  void fix_edges(const std::vector<EdgeRef>& edges);
  // VBC (Eqs. 6–12): at each end of each edge, a dashpot pair over half the
  // edge length: traction −ρ(C_P v_n n + C_S v_s s), n the outward normal,
  // with ρ, C_P = sqrt((K + 4G/3)/ρ), C_S = sqrt(G/ρ) of the edge's block.
  int add_viscous_boundary(const std::vector<EdgeRef>& edges);
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
  std::span<const Vec2> block_initial_vertices(BlockId b) const;  // as added (counter-clockwise)
  int block_edge_joint(BlockId b, int edge) const;
  Vec2 block_centroid(BlockId b) const { return centroid_[check(b)]; }
  double block_area(BlockId b) const { return area_[check(b)]; }
  double block_mass(BlockId b) const { return mass_[check(b)]; }
  int block_material(BlockId b) const { return material_[check(b)]; }
  Vec3 block_stress(BlockId b) const { return stress_[check(b)]; }      // (σxx, σyy, τxy), tension +
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
  void prepare_first_step();  // validate the model once: materials, overlaps, g2 length
  void resolve_controls();    // validate controls, fill in automatic g0 and g1
  void detect_contacts();     // broad + narrow phase, carry states, linearise, matrix shape
  bool contact_list_is_stale() const;
  void save_contact_states();     // the contacts' iteration state at the start of a step
  void restore_contact_states();  // back to it, for a redo
  double contact_range() const;
  bool previous_step_had_long_solves() const;  // over 30 CG iterations per solve
  int solve_step(double dt);                   // loop { assemble, solve, check contacts }; 0 or a rejection
  void assemble_block_terms(double dt);        // elastic, inertia, stress, gravity per block
  void assemble_point_terms(double dt);        // loads, fixed points, targets, boundaries at t + Δt
  void assemble_contacts(
      bool all_rows);  // block terms + contact springs and friction (all rows, or those whose contacts changed)
  void predict_contact_states();  // the open-close iteration's first guess, from the warm start
  bool check_contacts();          // open-close decision; true when a contact changed
  // The solve's block motions, in one pass over the vertices: the largest
  // vertex displacement, and the first block whose moved outline would have
  // zero or negative area (-1: none). Keeps each vertex's motion for update().
  std::pair<double, BlockId> check_block_motion();
  double deepest_penetration() const;
  void update(double dt);  // move vertices, stresses, velocities, contacts; advance time

  Controls controls_;
  std::vector<RockMaterial> rocks_;
  std::vector<JointMaterial> joints_;

  // Hot per-block state (solver arrays, indexed by block id).
  std::vector<int> vertex_start_;  // block b owns vertices_[vertex_start_[b] .. vertex_start_[b+1])
  std::vector<Vec2> vertices_;
  std::vector<Vec2> initial_vertices_;  // parallel to vertices_: where each vertex started (cold)
  std::vector<int> edge_joint_;         // parallel to vertices_: joint of edge k → k+1
  std::vector<Vec2> centroid_, initial_centroid_;
  std::vector<double> area_, sxx_, syy_, sxy_, mass_;
  std::vector<int> material_;
  std::vector<Vec3> stress_;
  std::vector<Vec6> velocity_;
  std::vector<Vec6> last_displacement_;  // previous step's solution: the PCG warm start

  // Loads and constraints attached to material points.
  struct PointLoad {
    BlockId block;
    Vec2 point;
    Vec2 force;
  };
  struct FixedPoint {
    BlockId block;
    Vec2 point;
    Vec2 origin;
  };
  struct TrackedPoint {
    BlockId block;
    Vec2 point;
    Vec2 origin;
  };
  struct PressureLoad {
    std::vector<EdgeRef> edges;
    double pressure;
    History history;
    bool from_history;
  };
  struct PointLoadHistory {
    int load;
    Vec2 direction;
    History magnitude;
  };
  struct DisplacementTarget {
    BlockId block;
    Vec2 point;
    Vec2 origin;
    Vec2 direction;              // zero direction: both components
    Vec2 target = Vec2::Zero();  // current target (vector)
    History history;
    enum { Fixed, Displacement, Velocity } mode = Fixed;
  };
  // A VBC dashpot (matrix c, N·s/m) or an SBC spring (stiffness k, N/m) at a material point.
  struct BoundaryPoint {
    int boundary;
    BlockId block;
    Vec2 point;
    Vec2 origin;
    Eigen::Matrix2d c;
    double k;
    Vec2 force;
  };
  struct Boundary {
    BoundaryKind kind;
    int first, count;
  };
  std::vector<PressureLoad> pressure_loads_;
  std::vector<PointLoadHistory> point_load_histories_;
  std::vector<DisplacementTarget> targets_;
  std::vector<BoundaryPoint> boundary_points_;
  std::vector<Boundary> boundaries_;
  void check_edges(const std::vector<EdgeRef>& edges, const std::string& what) const;
  std::vector<PointLoad> point_loads_;
  std::vector<FixedPoint> fixed_points_;
  std::vector<TrackedPoint> tracked_;

  std::vector<Contact> contacts_;

  double time_ = 0;
  long steps_ = 0;
  double dt_ = 0;
  double half_height_ = 0;
  double auto_range_ = 0;  // the automatic contact range so far (only widens)
  bool prepared_ = false;
  StepStats last_stats_;
  std::unique_ptr<Impl> impl_;  // scratch buffers reused from step to step
};

}  // namespace dda
