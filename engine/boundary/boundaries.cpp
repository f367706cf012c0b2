// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "boundary/boundaries.hpp"

#include <algorithm>
#include <cmath>

#include "block/displacement.hpp"
#include "block/motion.hpp"
#include "core/error.hpp"
#include "core/load_check.hpp"

namespace dda {

// ---- Model building ---------------------------------------------------------

int Boundaries::add_fixed_point(BlockId b, const Vec2& point) {
  if (!point.allFinite()) throw Error(msg("fixed point on block ", b, ": point is not finite"));
  fixed_points_.push_back({b, point, point});
  fixed_from_edges_.push_back(0);
  return static_cast<int>(fixed_points_.size()) - 1;
}

void Boundaries::fix_edges(const Blocks& blocks, const std::vector<EdgeRef>& edges) {
  check_edges(blocks, edges, "fixed boundary");
  fixed_edges_.push_back(edges);
  add_fixed_points_on(blocks, edges);
}

void Boundaries::add_fixed_points_on(const Blocks& blocks, const std::vector<EdgeRef>& edges) {
  for (const EdgeRef& e : edges) {
    const auto v = blocks.outline(e.block);
    for (int end : {e.edge, (e.edge + 1) % static_cast<int>(v.size())}) {
      // One fixed point per block vertex, however many of its edges are fixed.
      bool present = false;
      for (const FixedPoint& f : fixed_points_) present |= f.block == e.block && f.origin == v[end];
      if (!present) {
        add_fixed_point(e.block, v[end]);
        fixed_from_edges_.back() = 1;
      }
    }
  }
}

int Boundaries::add_displacement_target(const Blocks& blocks, BlockId b, const Vec2& point, const Vec2& direction) {
  const std::string what = msg("displacement target ", targets_.size());
  if (b < 0 || static_cast<std::size_t>(b) >= blocks.count()) throw Error(msg(what, ": no block ", b));
  if (!point.allFinite()) throw Error(msg(what, ": point is not finite"));
  if (!direction.allFinite()) throw Error(msg(what, ": direction is not finite"));
  DisplacementTarget t;
  t.block = b;
  t.point = t.origin = point;
  t.direction = direction.norm() > 0 ? Vec2(direction.normalized()) : Vec2(Vec2::Zero());
  targets_.push_back(t);
  return static_cast<int>(targets_.size()) - 1;
}

std::vector<Boundaries::TargetPoint> Boundaries::edge_target_points(const Blocks& blocks,
                                                                    const std::vector<EdgeRef>& edges, bool directed,
                                                                    const Vec2& direction) const {
  std::vector<TargetPoint> points;
  std::vector<std::pair<BlockId, int>> vertices;  // (block, vertex) of each point
  for (const EdgeRef& e : edges) {
    const auto v = blocks.outline(e.block);
    const int n = static_cast<int>(v.size());
    const Vec2 d = (v[(e.edge + 1) % n] - v[e.edge]).normalized();
    const Vec2 inward(-d.y(), d.x());
    for (int k : {e.edge, (e.edge + 1) % n}) {
      const auto key = std::make_pair(e.block, k);
      const auto at = std::find(vertices.begin(), vertices.end(), key);
      if (at == vertices.end()) {
        vertices.push_back(key);
        points.push_back({e.block, v[k], inward});
      } else {
        points[at - vertices.begin()].direction += inward;
      }
    }
  }
  for (TargetPoint& p : points) {
    const Vec2 n = p.direction;
    p.direction = !directed              ? Vec2(Vec2::Zero())
                  : direction.norm() > 0 ? Vec2(direction.normalized())
                  : n.norm() > 0         ? Vec2(n.normalized())
                                         : Vec2(Vec2::UnitX());
  }
  return points;
}

std::vector<int> Boundaries::add_edge_targets(const Blocks& blocks, const std::vector<EdgeRef>& edges, bool directed,
                                              const Vec2& direction) {
  check_edges(blocks, edges, "edge targets");
  if (!direction.allFinite()) throw Error("edge targets: direction is not finite");
  EdgeTargets set{edges, directed, direction, {}};
  for (const TargetPoint& p : edge_target_points(blocks, edges, directed, direction))
    set.ids.push_back(add_displacement_target(blocks, p.block, p.point, p.direction));
  edge_targets_.push_back(set);
  return set.ids;
}

std::vector<int> Boundaries::edge_target_ids(int id) const {
  for (const EdgeTargets& set : edge_targets_)
    if (std::find(set.ids.begin(), set.ids.end(), id) != set.ids.end()) return set.ids;
  return {id};
}

const Boundaries::DisplacementTarget& Boundaries::target(int id) const {
  if (id < 0 || static_cast<std::size_t>(id) >= targets_.size()) throw Error(msg("no displacement target ", id));
  return targets_[id];
}

void Boundaries::set_target_displacement(int id, const Vec2& value) {
  DisplacementTarget& t = target(id);
  if (!value.allFinite()) throw Error(msg("displacement target ", id, ": target is not finite"));
  t.mode = DisplacementTarget::Fixed;
  t.target = t.direction.norm() > 0 ? Vec2(value.x() * t.direction) : value;
}

void Boundaries::set_target_history(int id, History displacement) {
  DisplacementTarget& t = target(id);
  if (t.direction.norm() == 0) throw Error(msg("displacement target ", id, ": a history needs a direction"));
  t.history = std::move(displacement);
  t.mode = DisplacementTarget::Displacement;
}

void Boundaries::set_target_velocity_history(int id, History velocity) {
  DisplacementTarget& t = target(id);
  if (t.direction.norm() == 0) throw Error(msg("displacement target ", id, ": a history needs a direction"));
  t.history = std::move(velocity);
  t.mode = DisplacementTarget::Velocity;
}

void Boundaries::set_target_acceleration_history(int id, History acceleration) {
  DisplacementTarget& t = target(id);
  if (t.direction.norm() == 0) throw Error(msg("displacement target ", id, ": a history needs a direction"));
  t.history = std::move(acceleration);
  t.mode = DisplacementTarget::Acceleration;
}

Vec2 Boundaries::target_point_displacement(int id) const { return target(id).point - target(id).origin; }
Vec2 Boundaries::target_value(int id) const { return target(id).target; }

int Boundaries::add_viscous_boundary(const Blocks& blocks, const std::vector<RockMaterial>& rocks,
                                     const std::vector<EdgeRef>& edges, int medium) {
  const int id = static_cast<int>(boundaries_.size());
  check_edges(blocks, edges, msg("viscous boundary ", id));
  Boundary b;
  b.kind = BoundaryKind::Viscous;
  b.edges = edges;
  b.medium = medium;
  const RockMaterial& rock = medium >= 0 ? rocks[medium] : rocks[blocks.material[edges.front().block]];
  b.zs = rock.density * s_wave_speed(rock);
  const double g = rock.youngs / (2 * (1 + rock.poisson)), k = rock.youngs / (3 * (1 - 2 * rock.poisson));
  b.zp = std::sqrt((k + 4 * g / 3) * rock.density);
  boundaries_.push_back(std::move(b));
  make_points(id, blocks, rocks, PlaneMode::Stress);
  return id;
}

int Boundaries::add_spring_boundary(const Blocks& blocks, const std::vector<EdgeRef>& edges, double p,
                                    bool per_length) {
  const int id = static_cast<int>(boundaries_.size());
  check_edges(blocks, edges, msg("spring boundary ", id));
  if (!std::isfinite(p) || p <= 0) throw Error(msg("spring boundary ", id, ": stiffness p must be positive, got ", p));
  Boundary b;
  b.kind = BoundaryKind::Spring;
  b.edges = edges;
  b.p = p;
  b.per_length = per_length;
  boundaries_.push_back(std::move(b));
  make_points(id, blocks, {}, PlaneMode::Stress);
  return id;
}

void Boundaries::set_incident_velocity(int id, History vx, History vy) {
  if (id < 0 || id >= static_cast<int>(boundaries_.size())) throw Error(msg("no boundary ", id));
  Boundary& b = boundaries_[id];
  if (b.kind != BoundaryKind::Viscous)
    throw Error(msg("boundary ", id, ": an incident wave needs a viscous boundary (this one is a spring boundary)"));
  b.incident = true;
  b.incident_vx = std::move(vx);
  b.incident_vy = std::move(vy);
}

int Boundaries::add_free_field(const Blocks& blocks, const std::vector<RockMaterial>& rocks, PlaneMode plane,
                               const std::vector<EdgeRef>& side, int base) {
  const int id = static_cast<int>(boundaries_.size());
  const std::string what = msg("free-field boundary ", id);
  check_edges(blocks, side, what);
  if (base < 0 || base >= id || boundaries_[base].kind != BoundaryKind::Viscous || !boundaries_[base].incident)
    throw Error(msg(what, ": base ", base,
                    " must be a compliant base (a viscous boundary with an incident wave) made before it"));
  Boundary b;
  b.kind = BoundaryKind::FreeField;
  b.edges = side;
  b.base = base;
  boundaries_.push_back(std::move(b));
  try {
    make_points(id, blocks, rocks, plane);
  } catch (...) {
    boundaries_.pop_back();
    throw;
  }
  return id;
}

void Boundaries::make_points(int id, const Blocks& blocks, const std::vector<RockMaterial>& rocks, PlaneMode plane) {
  Boundary& bd = boundaries_[id];
  bd.first = static_cast<int>(boundary_points_.size());
  if (bd.kind == BoundaryKind::Viscous) {
    for (const EdgeRef& e : bd.edges) {
      const auto v = blocks.outline(e.block);
      const Vec2 a = v[e.edge], b = v[(e.edge + 1) % v.size()];
      const double l = (b - a).norm();
      const Vec2 t = (b - a) / l, n(t.y(), -t.x());  // outward normal of a counter-clockwise outline
      const RockMaterial& rock = bd.medium >= 0 ? rocks[bd.medium] : rocks[blocks.material[e.block]];
      // Eq. 6: C_P from the bulk and shear moduli.
      const double g = rock.youngs / (2 * (1 + rock.poisson)), k = rock.youngs / (3 * (1 - 2 * rock.poisson));
      const double cp = std::sqrt((k + 4 * g / 3) / rock.density), cs = std::sqrt(g / rock.density);
      // Eq. 12: C = C_P n nᵀ + C_S s sᵀ; each end carries half the edge.
      const Eigen::Matrix2d c = 0.5 * l * rock.density * (cp * n * n.transpose() + cs * t * t.transpose());
      for (const Vec2& p : {a, b}) boundary_points_.push_back({id, e.block, p, p, c, 0.0, Vec2::Zero()});
    }
  } else if (bd.kind == BoundaryKind::Spring) {
    for (const EdgeRef& e : bd.edges) {
      const auto v = blocks.outline(e.block);
      const Vec2 a = v[e.edge], b = v[(e.edge + 1) % v.size()];
      const double k = bd.per_length ? bd.p * (b - a).norm() : bd.p;
      for (const Vec2& pt : {a, b})
        boundary_points_.push_back({id, e.block, pt, pt, Eigen::Matrix2d::Zero(), k, Vec2::Zero()});
    }
  } else {
    const std::string what = msg("free-field boundary ", id);
    // The side's edges, bottom to top; each vertical, one outward normal.
    struct SideEdge {
      EdgeRef edge;
      Vec2 low, high;
    };
    std::vector<SideEdge> edges;
    double normal_x = 0;
    for (const EdgeRef& e : bd.edges) {
      const auto v = blocks.outline(e.block);
      const Vec2 a = v[e.edge], b = v[(e.edge + 1) % v.size()];
      const double l = (b - a).norm();
      if (std::abs(b.x() - a.x()) > 1e-6 * l)
        throw Error(
            msg(what, ": edge ", e.edge, " of block ", e.block, " is not vertical (a free-field side must be)"));
      const double nx = b.y() > a.y() ? 1.0 : -1.0;  // outward normal (t.y, −t.x) of a counter-clockwise outline
      if (normal_x != 0 && nx != normal_x)
        throw Error(msg(what, ": the edges face both ways; give the left and the right side as two free fields"));
      normal_x = nx;
      edges.push_back({e, a.y() < b.y() ? a : b, a.y() < b.y() ? b : a});
    }
    std::sort(edges.begin(), edges.end(), [](const SideEdge& p, const SideEdge& q) { return p.low.y() < q.low.y(); });
    std::vector<FreeFieldColumn::Segment> segments;
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const double l = edges[i].high.y() - edges[i].low.y();
      if (i > 0 && std::abs(edges[i].low.y() - edges[i - 1].high.y()) > 1e-6 * l)
        throw Error(msg(what, ": the side has a gap or an overlap at y = ", edges[i - 1].high.y(),
                        " (give every edge of the side, once)"));
      const RockMaterial& rock = rocks[blocks.material[edges[i].edge.block]];
      const Mat3 e = elastic_matrix(rock, plane);
      segments.push_back({l, rock.density, e(2, 2), e(0, 1)});
    }
    const Boundary& base = boundaries_[bd.base];
    columns_.emplace_back(edges.front().low.y(), std::move(segments), base.zs, base.zp, base.incident_vx,
                          base.incident_vy);
    bd.column = static_cast<int>(columns_.size()) - 1;
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const EdgeRef& e = edges[i].edge;
      const RockMaterial& rock = rocks[blocks.material[e.block]];
      const double l = edges[i].high.y() - edges[i].low.y();
      const double g = rock.youngs / (2 * (1 + rock.poisson)), k = rock.youngs / (3 * (1 - 2 * rock.poisson));
      const double cp = std::sqrt((k + 4 * g / 3) / rock.density), cs = std::sqrt(g / rock.density);
      Eigen::Matrix2d c = Eigen::Matrix2d::Zero();
      c(0, 0) = 0.5 * l * rock.density * cp;
      c(1, 1) = 0.5 * l * rock.density * cs;
      for (int end = 0; end < 2; ++end) {
        BoundaryPoint p{id, e.block, end == 0 ? edges[i].low : edges[i].high, {}, c, 0.0, Vec2::Zero()};
        p.origin = p.point;
        p.node = static_cast<int>(i) + end;
        p.segment = static_cast<int>(i);
        p.half_length = 0.5 * l;
        p.normal_x = normal_x;
        boundary_points_.push_back(p);
      }
    }
  }
  bd.count = static_cast<int>(boundary_points_.size()) - bd.first;
}

Vec2 Boundaries::free_field_velocity(int id, double y) const {
  if (id < 0 || id >= static_cast<int>(boundaries_.size()) || boundaries_[id].kind != BoundaryKind::FreeField)
    throw Error(msg("no free-field boundary ", id));
  const FreeFieldColumn& column = columns_[boundaries_[id].column];
  const int node = column.node_at(y);
  return Vec2(column.vx(node), column.vy(node));
}

Vec2 Boundaries::free_field_load(const BoundaryPoint& p) const {
  const FreeFieldColumn& column = columns_[boundaries_[p.boundary].column];
  const Vec2 v_ff(column.vx(p.node), column.vy(p.node));
  const Vec2 traction = p.normal_x * Vec2(column.lateral_stress(p.segment), column.shear_stress(p.segment));
  return p.c * v_ff + p.half_length * traction;
}

std::vector<Vec2> Boundaries::boundary_point_forces(int id) const {
  if (id < 0 || id >= static_cast<int>(boundaries_.size())) throw Error(msg("no boundary ", id));
  std::vector<Vec2> f;
  for (int i = 0; i < boundaries_[id].count; ++i) f.push_back(boundary_points_[boundaries_[id].first + i].force);
  return f;
}

// ---- The step ---------------------------------------------------------------

void Boundaries::add_terms(double t_end, double stiff_spring, const Blocks& blocks, const TimeScheme& scheme,
                           BlockTerms& terms) {
  // A spring of stiffness matrix k pulling the point towards `goal`.
  auto add_spring = [&](BlockId b, const Vec2& at, const Eigen::Matrix2d& k, const Vec2& goal) {
    const Mat26 t = displacement_matrix(at, blocks.centroid[b]);
    terms.k[b] = Symmetric6(terms.k[b].full() + t.transpose() * k * t);
    terms.f[b] += t.transpose() * (k * (goal - at));
  };
  const double kf = stiff_spring;
  const Eigen::Matrix2d stiff = kf * Eigen::Matrix2d::Identity();
  // Fixed points: back to where they started, residual included.
  for (const FixedPoint& p : fixed_points_) add_spring(p.block, p.point, stiff, p.origin);

  // DHI: towards start + target, along the direction only when one is given.
  for (DisplacementTarget& t : targets_) {
    if (t.mode == DisplacementTarget::Displacement) t.target = t.history.value(t_end) * t.direction;
    if (t.mode == DisplacementTarget::Velocity) t.target = t.history.integral(t_end) * t.direction;
    if (t.mode == DisplacementTarget::Acceleration) t.target = t.history.double_integral(t_end) * t.direction;
    if (t.direction.norm() > 0) {
      // Only the component along the direction is driven: goal = point moved
      // along the direction by what is still missing.
      const double missing = (t.origin + t.target - t.point).dot(t.direction);
      add_spring(t.block, t.point, kf * t.direction * t.direction.transpose(), t.point + missing * t.direction);
    } else {
      add_spring(t.block, t.point, stiff, t.origin + t.target);
    }
  }

  // VBC dashpots and SBC springs. A dashpot's force at the end-of-step
  // velocity v1 = velocity_factor·T·D − T·carried_velocity is −c·v1: its
  // derivative joins the matrix, the rest the right-hand side. An incident
  // wave adds 2·c·v_in(t_end), a load.
  for (Boundary& b : boundaries_)
    if (b.incident) b.incident_velocity = Vec2(b.incident_vx.value(t_end), b.incident_vy.value(t_end));
  for (FreeFieldColumn& column : columns_) column.advance(t_end, scheme);
  for (const BoundaryPoint& p : boundary_points_) {
    const Mat26 t = displacement_matrix(p.point, blocks.centroid[p.block]);
    const Boundary& boundary = boundaries_[p.boundary];
    if (boundary.kind != BoundaryKind::Spring) {
      terms.k[p.block] = Symmetric6(terms.k[p.block].full() + scheme.velocity_factor() * t.transpose() * p.c * t);
      terms.f[p.block] += t.transpose() * (p.c * (t * scheme.carried_velocity(blocks.scheme_state(p.block))));
      if (boundary.incident) terms.f[p.block] += t.transpose() * (2 * (p.c * boundary.incident_velocity));
      if (boundary.kind == BoundaryKind::FreeField) terms.f[p.block] += t.transpose() * free_field_load(p);
    } else {
      // SBC: the fixed-point sub-matrix without the fixed point's residual
      // term (the paper's §3.3.1): the spring acts on this step's
      // displacement only, so it draws p·l·Δu from a moving boundary.
      add_spring(p.block, p.point, p.k * Eigen::Matrix2d::Identity(), p.point);
    }
  }
}

Boundaries::Work Boundaries::step_work(double t0, double t_end, double stiff_spring, const Blocks& blocks,
                                       const VecX& d, const TimeScheme& scheme) const {
  Work w;
  auto d_of = [&](BlockId b) -> Vec6 { return d.segment<6>(6 * b); };
  // A spring pulling `point` towards `goal` (along `direction` only when it is not zero).
  auto spring_force = [&](const Vec2& point, const Vec2& goal, const Vec2& direction) -> Vec2 {
    if (direction.norm() > 0) return stiff_spring * direction * (goal - point).dot(direction);
    return stiff_spring * (goal - point);
  };
  for (const FixedPoint& p : fixed_points_) {
    const Vec2 du = point_displacement(p.point, blocks.centroid[p.block], d_of(p.block));
    w.fixed_points +=
        0.5 *
        (spring_force(p.point, p.origin, Vec2::Zero()) + spring_force(p.point + du, p.origin, Vec2::Zero())).dot(du);
  }
  for (const DisplacementTarget& t : targets_) {
    auto target_at = [&](double time) -> Vec2 {
      if (t.mode == DisplacementTarget::Displacement) return t.history.value(time) * t.direction;
      if (t.mode == DisplacementTarget::Velocity) return t.history.integral(time) * t.direction;
      return t.target;
    };
    const Vec2 du = point_displacement(t.point, blocks.centroid[t.block], d_of(t.block));
    w.targets += 0.5 * (spring_force(t.point, t.origin + target_at(t0), t.direction) +
                        spring_force(t.point + du, t.origin + target_at(t_end), t.direction))
                           .dot(du);
  }
  for (const BoundaryPoint& p : boundary_points_) {
    const Mat26 t = displacement_matrix(p.point, blocks.centroid[p.block]);
    const Vec2 du = t * d_of(p.block);
    if (boundaries_[p.boundary].kind == BoundaryKind::Viscous) {
      const BlockState s = blocks.scheme_state(p.block);
      const Vec2 before = -p.c * (t * s.velocity), after = -p.c * (t * scheme.end_velocity(d_of(p.block), s));
      w.viscous += 0.5 * (before + after).dot(du);
    } else {
      w.springs += -0.5 * p.k * du.squaredNorm();
    }
  }
  return w;
}

std::vector<char> Boundaries::held_blocks(std::size_t count) const {
  std::vector<char> held(count, 0);
  for (const FixedPoint& f : fixed_points_) held[f.block] = 1;
  for (const DisplacementTarget& t : targets_) held[t.block] = 1;
  return held;
}

std::vector<LoadSignal> Boundaries::dynamic_signals() const {
  std::vector<LoadSignal> signals;
  for (std::size_t i = 0; i < targets_.size(); ++i) {
    const DisplacementTarget& t = targets_[i];
    if (t.mode == DisplacementTarget::Fixed) continue;
    const SignalKind kind = t.mode == DisplacementTarget::Displacement ? SignalKind::Displacement
                            : t.mode == DisplacementTarget::Velocity   ? SignalKind::Velocity
                                                                       : SignalKind::Acceleration;
    signals.push_back({t.history.points(), kind, msg("displacement target ", i)});
  }
  for (std::size_t i = 0; i < boundaries_.size(); ++i)
    if (boundaries_[i].incident) {
      signals.push_back({boundaries_[i].incident_vx.points(), SignalKind::Velocity, msg("incident wave ", i, " (x)")});
      signals.push_back({boundaries_[i].incident_vy.points(), SignalKind::Velocity, msg("incident wave ", i, " (y)")});
    }
  return signals;
}

void Boundaries::remesh(const Remeshing& r, const std::vector<RockMaterial>& rocks, PlaneMode plane) {
  const Blocks& blocks = *r.blocks;
  // Fixed points: those of fixed edges made again on the edges there now.
  std::vector<FixedPoint> single;
  for (std::size_t i = 0; i < fixed_points_.size(); ++i)
    if (!fixed_from_edges_[i]) {
      FixedPoint f = fixed_points_[i];
      f.block = r.element_at(f.block, f.origin);
      single.push_back(f);
    }
  fixed_points_ = std::move(single);
  fixed_from_edges_.assign(fixed_points_.size(), 0);
  for (std::vector<EdgeRef>& edges : fixed_edges_) {
    edges = r.edges(edges);
    add_fixed_points_on(blocks, edges);
  }
  // Targets: each to the element under it; a set made on edges gains the
  // points along them (the input of its first target: all of a set's
  // targets are driven alike).
  for (DisplacementTarget& t : targets_) t.block = r.element_at(t.block, t.origin);
  for (EdgeTargets& set : edge_targets_) {
    set.edges = r.edges(set.edges);
    const DisplacementTarget input = targets_[set.ids.front()];
    std::vector<int> ids;
    for (const TargetPoint& p : edge_target_points(blocks, set.edges, set.directed, set.direction)) {
      int id = -1;
      for (int old : set.ids)
        if ((targets_[old].origin - p.point).norm() <= 1e-9 * (1 + p.point.norm())) id = old;
      if (id < 0) {
        DisplacementTarget t = input;
        id = static_cast<int>(targets_.size());
        targets_.push_back(t);
      }
      DisplacementTarget& t = targets_[id];
      t.block = p.block;
      t.point = t.origin = p.point;
      t.direction = p.direction;
      if (t.mode == DisplacementTarget::Fixed && input.direction.norm() > 0)
        t.target = input.target.dot(input.direction) * t.direction;
      ids.push_back(id);
    }
    set.ids = std::move(ids);
  }
  // Viscous, spring and free-field boundaries: their points made again.
  boundary_points_.clear();
  columns_.clear();
  for (std::size_t id = 0; id < boundaries_.size(); ++id) {
    boundaries_[id].edges = r.edges(boundaries_[id].edges);
    make_points(static_cast<int>(id), blocks, rocks, plane);
  }
}

void Boundaries::update(const Blocks& blocks, const VecX& d_all, const TimeScheme& scheme) {
  auto d_of = [&](BlockId b) -> Vec6 { return d_all.segment<6>(6 * b); };
  auto moved = [&](BlockId b, const Vec2& p) { return point_displacement(p, blocks.centroid[b], d_of(b)); };
  move_material_points(fixed_points_, blocks, d_all);
  for (DisplacementTarget& p : targets_) p.point += moved(p.block, p.point);
  for (BoundaryPoint& p : boundary_points_) {
    // Force at the end of the step: c·(2·v_in − v1) (dashpot, v_in = 0
    // without an incident wave), plus the free field's load, or −k·Δu (spring).
    const Vec2 du = moved(p.block, p.point);
    const Boundary& b = boundaries_[p.boundary];
    if (b.kind != BoundaryKind::Spring) {
      const Mat26 t = displacement_matrix(p.point, blocks.centroid[p.block]);
      p.force = p.c * ((b.incident ? Vec2(2 * b.incident_velocity) : Vec2(Vec2::Zero())) -
                       t * scheme.end_velocity(d_of(p.block), blocks.scheme_state(p.block)));
      if (b.kind == BoundaryKind::FreeField) p.force += free_field_load(p);
    } else {
      p.force = -p.k * du;
    }
    p.point += du;
  }
  for (FreeFieldColumn& column : columns_) column.commit();
}

void Boundaries::check_loaded(const LoadCheck& check, const Blocks& blocks) const {
  for (std::size_t i = 0; i < fixed_points_.size(); ++i)
    dda::check_loaded(check, fixed_points_[i], blocks, msg("fixed point ", i));
  for (std::size_t i = 0; i < targets_.size(); ++i) {
    const DisplacementTarget& t = targets_[i];
    check.index(t.block, blocks.count(), "blocks", "displacement target ", i, "'s block");
    check.require(t.point.allFinite() && t.origin.allFinite() && t.direction.allFinite() && t.target.allFinite(),
                  "displacement target ", i, " is not finite");
  }
  for (std::size_t b = 0; b < boundaries_.size(); ++b) {
    const Boundary& g = boundaries_[b];
    check.require(g.first >= 0 && g.count >= 0 && g.first <= static_cast<long long>(boundary_points_.size()) - g.count,
                  "boundary ", b, "'s points ", g.first, " to ", static_cast<long long>(g.first) + g.count, " of ",
                  boundary_points_.size());
    if (g.kind == BoundaryKind::FreeField)
      check.index(g.column, columns_.size(), "free-field columns", "free-field boundary ", b, "'s column");
  }
  for (std::size_t i = 0; i < boundary_points_.size(); ++i) {
    const BoundaryPoint& p = boundary_points_[i];
    check.index(p.boundary, boundaries_.size(), "boundaries", "boundary point ", i, "'s boundary");
    check.index(p.block, blocks.count(), "blocks", "boundary point ", i, "'s block");
    const Boundary& g = boundaries_[p.boundary];
    check.require(static_cast<long long>(i) >= g.first && static_cast<long long>(i) < g.first + g.count,
                  "boundary point ", i, " is not among its boundary's points");
    if (g.kind != BoundaryKind::FreeField) continue;
    const FreeFieldColumn& column = columns_[g.column];
    check.index(p.node, static_cast<std::size_t>(column.nodes()), "column nodes", "boundary point ", i, "'s node");
    check.index(p.segment, static_cast<std::size_t>(column.nodes() - 1), "column segments", "boundary point ", i,
                "'s segment");
  }
}

}  // namespace dda
