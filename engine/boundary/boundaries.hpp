// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Boundary conditions at material points of the blocks: fixed points,
// prescribed displacements (the paper's DHI), viscous boundaries (VBC) and
// spring boundaries (SBC). What a model holds, their terms in each step, and
// the forces they exerted in the last one.
#include <utility>
#include <vector>

#include "assembly/block_terms.hpp"
#include "block/blocks.hpp"
#include "block/remeshing.hpp"
#include "block/time_scheme.hpp"
#include "boundary/free_field.hpp"
#include "core/material.hpp"
#include "loading/history.hpp"
#include "loading/load_frequency.hpp"

namespace dda {

enum class BoundaryKind { Viscous, Spring, FreeField };
constexpr BoundaryKind enum_last(BoundaryKind) { return BoundaryKind::FreeField; }  // (core/archive.hpp)

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
  // Targets at the end points of edges, once per block vertex: directed,
  // along `direction` when it is not zero, else along the edges' inward
  // normal (the mean of the normals where two edges of the set meet); not
  // directed, in both components. Returns the targets' ids; the edges are
  // kept, so that the set follows its edges when the blocks are meshed
  // (remesh).
  std::vector<int> add_edge_targets(const Blocks& blocks, const std::vector<EdgeRef>& edges, bool directed,
                                    const Vec2& direction);
  // The ids of the targets of the add_edge_targets call that made target
  // `id` (all of them, as they are after a remesh); {id} for another target.
  std::vector<int> edge_target_ids(int id) const;
  void set_target_displacement(int id, const Vec2& target);            // along a direction: target.x() is the magnitude
  void set_target_history(int id, History displacement);               // magnitude along the direction
  void set_target_velocity_history(int id, History velocity);          // integrated to displacement
  void set_target_acceleration_history(int id, History acceleration);  // integrated twice, from rest
  Vec2 target_point_displacement(int id) const;
  Vec2 target_value(int id) const;
  std::size_t fixed_point_count() const { return fixed_points_.size(); }
  std::size_t target_count() const { return targets_.size(); }

  // VBC (Eqs. 6–12) and SBC (Eq. 22), on the edges' end points. A viscous
  // boundary takes ρ, C_P and C_S from each edge's block, or from `medium`
  // when given (the half-space below a compliant base).
  int add_viscous_boundary(const Blocks& blocks, const std::vector<RockMaterial>& rocks,
                           const std::vector<EdgeRef>& edges, int medium = -1);
  // A compliant (quiet) base: the viscous boundary also carries the stress of
  // a wave arriving from outside, particle velocity v_in(t) = (vx, vy): each
  // point's force becomes C·(2·v_in − v), i.e. traction 2ρC·v_in less the
  // dashpot's (UDEC's input; what leaves through the boundary is absorbed).
  void set_incident_velocity(int id, History vx, History vy);
  // Free-field side (free_field.hpp): a vertical side of the model (edges
  // with one outward normal, ±x) coupled to a 1-D column beside it, driven
  // by the incident wave of the compliant base `base` (a viscous boundary
  // with set_incident_velocity). At each end of each edge: the viscous
  // boundary's dashpots against the column's velocity, C·(v_ff − v), plus
  // the column's stress on the side, (σxx, τxy)·n_x over half the edge.
  int add_free_field(const Blocks& blocks, const std::vector<RockMaterial>& rocks, PlaneMode plane,
                     const std::vector<EdgeRef>& side, int base);
  // The column's velocity at the node nearest height y (after the last step).
  Vec2 free_field_velocity(int id, double y) const;
  int add_spring_boundary(const Blocks& blocks, const std::vector<EdgeRef>& edges, double p, bool per_length);
  std::vector<Vec2> boundary_point_forces(int id) const;
  // Whether a boundary moves the blocks (a displacement target, an incident
  // wave), not only holds or resists them (fixed points, springs, dashpots).
  bool drives_motion() const {
    for (const Boundary& b : boundaries_)
      if (b.incident) return true;
    return !targets_.empty();
  }

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
  // Per block (of `count`): 1 where a fixed point or a displacement target
  // holds it (the landing law's immovable blocks, contact/landing.hpp).
  std::vector<char> held_blocks(std::size_t count) const;

  // The prescribed motions and incident waves, as wave signals
  // (loading/load_frequency.hpp).
  std::vector<LoadSignal> dynamic_signals() const;
  // After first-order blocks were meshed in place (before the first step):
  // points go to the element under them, and what was given on edges is
  // made again on the edges that now stand there (fixed edges, edge
  // targets, viscous, spring and free-field boundaries); every id stays.
  void remesh(const Remeshing& r, const std::vector<RockMaterial>& rocks, PlaneMode plane);

  // What a checkpoint holds (core/archive.hpp): every point with its state.
  template <class Archive>
  void fields(Archive& ar) {
    ar(fixed_points_, fixed_from_edges_, fixed_edges_, targets_, edge_targets_, boundary_points_, boundaries_,
       columns_);
  }
  // Read from a checkpoint: every block, point, boundary, column and node in
  // range (core/load_check.hpp).
  void check_loaded(const LoadCheck& check, const Blocks& blocks) const;

 private:
  using FixedPoint = MaterialPoint;
  struct DisplacementTarget {
    BlockId block;
    Vec2 point;
    Vec2 origin;
    Vec2 direction;              // zero direction: both components
    Vec2 target = Vec2::Zero();  // current target (vector)
    History history;
    enum Mode { Fixed, Displacement, Velocity, Acceleration } mode = Fixed;
    friend constexpr Mode enum_last(Mode) { return Acceleration; }  // (core/archive.hpp)
    template <class Archive>
    void fields(Archive& ar) {
      ar(block, point, origin, direction, target, history, mode);
    }
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
    // Free-field points: the column node at this point and the segment of its edge.
    int node = -1, segment = -1;
    double half_length = 0;
    double normal_x = 0;  // the side's outward normal, ±1 along x
    template <class Archive>
    void fields(Archive& ar) {
      ar(boundary, block, point, origin, c, k, force, node, segment, half_length, normal_x);
    }
  };
  struct Boundary {
    BoundaryKind kind;
    int first, count;
    bool incident = false;  // a viscous boundary with an incident wave
    History incident_vx, incident_vy;
    Vec2 incident_velocity = Vec2::Zero();  // at the end of the last step assembled
    double zs = 0, zp = 0;                  // viscous: impedances ρC_S, ρC_P of its medium
    int column = -1;                        // free field: its column in columns_
    // What it was made from (its points are made again from these when the
    // blocks are meshed): its edges; viscous: the medium (-1: each edge's
    // block); spring: p and per_length; free field: the base.
    std::vector<EdgeRef> edges;
    int medium = -1, base = -1;
    double p = 0;
    bool per_length = true;
    template <class Archive>
    void fields(Archive& ar) {
      ar(kind, first, count, incident, incident_vx, incident_vy, incident_velocity, zs, zp, column, edges, medium, base,
         p, per_length);
    }
  };
  // A set of targets made on edges (add_edge_targets).
  struct EdgeTargets {
    std::vector<EdgeRef> edges;
    bool directed = true;
    Vec2 direction;  // zero: the edges' inward normals
    std::vector<int> ids;
    template <class Archive>
    void fields(Archive& ar) {
      ar(edges, directed, direction, ids);
    }
  };
  // The force of a free-field point at the trial state: C·(v_ff − v1) + traction.
  Vec2 free_field_load(const BoundaryPoint& p) const;
  // The points of boundary `id` (boundaries_[id], its edges) appended to
  // boundary_points_ (and, for a free field, its column to columns_).
  void make_points(int id, const Blocks& blocks, const std::vector<RockMaterial>& rocks, PlaneMode plane);
  void add_fixed_points_on(const Blocks& blocks, const std::vector<EdgeRef>& edges);
  // (block, point, direction) of the targets on edges, in order.
  struct TargetPoint {
    BlockId block;
    Vec2 point, direction;
  };
  std::vector<TargetPoint> edge_target_points(const Blocks& blocks, const std::vector<EdgeRef>& edges, bool directed,
                                              const Vec2& direction) const;
  const DisplacementTarget& target(int id) const;
  DisplacementTarget& target(int id) { return const_cast<DisplacementTarget&>(std::as_const(*this).target(id)); }

  std::vector<FixedPoint> fixed_points_;
  std::vector<char> fixed_from_edges_;             // per fixed point: made by fix_edges
  std::vector<std::vector<EdgeRef>> fixed_edges_;  // each fix_edges call's edges
  std::vector<DisplacementTarget> targets_;
  std::vector<EdgeTargets> edge_targets_;
  std::vector<BoundaryPoint> boundary_points_;
  std::vector<Boundary> boundaries_;
  std::vector<FreeFieldColumn> columns_;
};

}  // namespace dda
