#pragma once
// Boundary conditions at material points of the blocks: fixed points,
// prescribed displacements (the paper's DHI), viscous boundaries (VBC) and
// spring boundaries (SBC). What a model holds, their terms in each step, and
// the forces they exerted in the last one.
#include <utility>
#include <vector>

#include "assembly/block_terms.hpp"
#include "block/blocks.hpp"
#include "block/time_scheme.hpp"
#include "core/material.hpp"
#include "loading/history.hpp"

namespace dda {

enum class BoundaryKind { Viscous, Spring };

class Boundaries {
 public:
  // A fixed point: a stiff spring (fixed_point_factor × g0) that pulls the
  // material point back to where it started, residual included. The block
  // is checked by the caller.
  int add_fixed_point(BlockId b, const Vec2& point);
  // Fixed points at both ends of each edge (one per block vertex).
  void fix_edges(const Blocks& blocks, const std::vector<EdgeRef>& edges);

  // DHI: a stiff spring pulls the material point to start + target; with a
  // direction (normalised) along it only, the target a magnitude along it.
  int add_displacement_target(const Blocks& blocks, BlockId b, const Vec2& point, const Vec2& direction);
  void set_target_displacement(int id, const Vec2& target);    // along a direction: target.x() is the magnitude
  void set_target_history(int id, History displacement);       // magnitude along the direction
  void set_target_velocity_history(int id, History velocity);  // integrated to displacement
  Vec2 target_point_displacement(int id) const;
  Vec2 target_value(int id) const;

  // VBC (Eqs. 6–12) and SBC (Eq. 22), on the edges' end points.
  int add_viscous_boundary(const Blocks& blocks, const std::vector<RockMaterial>& rocks,
                           const std::vector<EdgeRef>& edges);
  int add_spring_boundary(const Blocks& blocks, const std::vector<EdgeRef>& edges, double p, bool per_length);
  std::vector<Vec2> boundary_point_forces(int id) const;

  // The step: springs and dashpots into the block terms, serially in a fixed
  // order (fixed points, targets at t_end, boundary points). stiff_spring is
  // fixed_point_factor × g0.
  void add_terms(double t_end, double stiff_spring, const Blocks& blocks, const TimeScheme& scheme, BlockTerms& terms);
  // The accepted step's displacement d: the points move with their blocks
  // (before the blocks themselves move) and the boundary points record the
  // force they exerted.
  void update(const Blocks& blocks, const VecX& d, const TimeScheme& scheme);
  // The work (J/m) each kind did on the blocks over the accepted step d
  // (before update), trapezoidal between its forces at the step's start and
  // end: fixed points and DHI targets (springs to where they should be, the
  // targets at t0 and t_end), VBC dashpots (at the start and end velocities:
  // negative, what they absorbed) and SBC springs (from zero, as the step
  // applies them, to −k·Δu: negative).
  struct Work {
    double fixed_points = 0, targets = 0, viscous = 0, springs = 0;
  };
  Work step_work(double t0, double t_end, double stiff_spring, const Blocks& blocks, const VecX& d,
                 const TimeScheme& scheme) const;

 private:
  using FixedPoint = MaterialPoint;
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
  const DisplacementTarget& target(int id) const;
  DisplacementTarget& target(int id) { return const_cast<DisplacementTarget&>(std::as_const(*this).target(id)); }

  std::vector<FixedPoint> fixed_points_;
  std::vector<DisplacementTarget> targets_;
  std::vector<BoundaryPoint> boundary_points_;
  std::vector<Boundary> boundaries_;
};

}  // namespace dda
