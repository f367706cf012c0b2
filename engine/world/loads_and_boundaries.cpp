// Model building for loads and boundaries on edges (SHI, FHI, DHI, Fixed,
// VBC, SBC). Their contributions to each step are in step.cpp
// (assemble_point_terms).
#include <cmath>

#include "core/error.hpp"
#include "world/world.hpp"

namespace dda {

void World::check_edges(const std::vector<EdgeRef>& edges, const std::string& what) const {
  if (edges.empty()) throw Error(msg(what, ": no edges given"));
  for (const EdgeRef& e : edges) {
    if (e.block < 0 || static_cast<std::size_t>(e.block) >= block_count())
      throw Error(msg(what, ": no block ", e.block));
    const int n = vertex_start_[e.block + 1] - vertex_start_[e.block];
    if (e.edge < 0 || e.edge >= n)
      throw Error(msg(what, ": block ", e.block, " has no edge ", e.edge, " (it has ", n, ")"));
  }
}

int World::add_pressure_load(const std::vector<EdgeRef>& edges, double pressure) {
  const std::string what = msg("pressure load ", pressure_loads_.size());
  check_edges(edges, what);
  if (!std::isfinite(pressure)) throw Error(msg(what, ": pressure is not finite"));
  pressure_loads_.push_back({edges, pressure, History(), false});
  return static_cast<int>(pressure_loads_.size()) - 1;
}

void World::set_pressure(int id, double pressure) {
  if (id < 0 || id >= static_cast<int>(pressure_loads_.size())) throw Error(msg("no pressure load ", id));
  if (!std::isfinite(pressure)) throw Error(msg("pressure load ", id, ": pressure is not finite"));
  pressure_loads_[id].pressure = pressure;
  pressure_loads_[id].from_history = false;
}

void World::set_pressure_history(int id, History pressure) {
  if (id < 0 || id >= static_cast<int>(pressure_loads_.size())) throw Error(msg("no pressure load ", id));
  pressure_loads_[id].history = std::move(pressure);
  pressure_loads_[id].from_history = true;
}

void World::set_point_load_history(int id, const Vec2& direction, History magnitude) {
  if (id < 0 || id >= static_cast<int>(point_loads_.size())) throw Error(msg("no point load ", id));
  if (!direction.allFinite() || direction.norm() == 0)
    throw Error(msg("point load ", id, ": direction must be a non-zero vector"));
  for (PointLoadHistory& h : point_load_histories_)
    if (h.load == id) {
      h = {id, direction, std::move(magnitude)};
      return;
    }
  point_load_histories_.push_back({id, direction, std::move(magnitude)});
}

int World::add_displacement_target(BlockId b, const Vec2& point, const Vec2& direction) {
  const std::string what = msg("displacement target ", targets_.size());
  if (b < 0 || static_cast<std::size_t>(b) >= block_count()) throw Error(msg(what, ": no block ", b));
  if (!point.allFinite()) throw Error(msg(what, ": point is not finite"));
  if (!direction.allFinite()) throw Error(msg(what, ": direction is not finite"));
  DisplacementTarget t;
  t.block = b;
  t.point = t.origin = point;
  t.direction = direction.norm() > 0 ? Vec2(direction.normalized()) : Vec2(Vec2::Zero());
  targets_.push_back(t);
  return static_cast<int>(targets_.size()) - 1;
}

static void check_target(int id, std::size_t n) {
  if (id < 0 || static_cast<std::size_t>(id) >= n) throw Error(msg("no displacement target ", id));
}

void World::set_target_displacement(int id, const Vec2& target) {
  check_target(id, targets_.size());
  if (!target.allFinite()) throw Error(msg("displacement target ", id, ": target is not finite"));
  DisplacementTarget& t = targets_[id];
  t.mode = DisplacementTarget::Fixed;
  t.target = t.direction.norm() > 0 ? Vec2(target.x() * t.direction) : target;
}

void World::set_target_history(int id, History displacement) {
  check_target(id, targets_.size());
  if (targets_[id].direction.norm() == 0) throw Error(msg("displacement target ", id, ": a history needs a direction"));
  targets_[id].history = std::move(displacement);
  targets_[id].mode = DisplacementTarget::Displacement;
}

void World::set_target_velocity_history(int id, History velocity) {
  check_target(id, targets_.size());
  if (targets_[id].direction.norm() == 0) throw Error(msg("displacement target ", id, ": a history needs a direction"));
  targets_[id].history = std::move(velocity);
  targets_[id].mode = DisplacementTarget::Velocity;
}

Vec2 World::target_point_displacement(int id) const {
  check_target(id, targets_.size());
  return targets_[id].point - targets_[id].origin;
}

Vec2 World::target_value(int id) const {
  check_target(id, targets_.size());
  return targets_[id].target;
}

void World::fix_edges(const std::vector<EdgeRef>& edges) {
  check_edges(edges, "fixed boundary");
  for (const EdgeRef& e : edges) {
    const auto v = block_vertices(e.block);
    for (int end : {e.edge, (e.edge + 1) % static_cast<int>(v.size())}) {
      // One fixed point per block vertex, however many of its edges are fixed.
      bool present = false;
      for (const FixedPoint& f : fixed_points_) present |= f.block == e.block && f.origin == v[end];
      if (!present) add_fixed_point(e.block, v[end]);
    }
  }
}

int World::add_viscous_boundary(const std::vector<EdgeRef>& edges) {
  const int id = static_cast<int>(boundaries_.size());
  check_edges(edges, msg("viscous boundary ", id));
  const int first = static_cast<int>(boundary_points_.size());
  for (const EdgeRef& e : edges) {
    const auto v = block_vertices(e.block);
    const Vec2 a = v[e.edge], b = v[(e.edge + 1) % v.size()];
    const double l = (b - a).norm();
    const Vec2 t = (b - a) / l, n(t.y(), -t.x());  // outward normal of a counter-clockwise outline
    const RockMaterial& rock = rocks_[material_[e.block]];
    // Eq. 6: C_P from the bulk and shear moduli.
    const double g = rock.youngs / (2 * (1 + rock.poisson)), k = rock.youngs / (3 * (1 - 2 * rock.poisson));
    const double cp = std::sqrt((k + 4 * g / 3) / rock.density), cs = std::sqrt(g / rock.density);
    // Eq. 12: C = C_P n nᵀ + C_S s sᵀ; each end carries half the edge.
    const Eigen::Matrix2d c = 0.5 * l * rock.density * (cp * n * n.transpose() + cs * t * t.transpose());
    for (const Vec2& p : {a, b}) boundary_points_.push_back({id, e.block, p, p, c, 0.0, Vec2::Zero()});
  }
  boundaries_.push_back({BoundaryKind::Viscous, first, static_cast<int>(boundary_points_.size()) - first});
  return id;
}

int World::add_spring_boundary(const std::vector<EdgeRef>& edges, double p, bool per_length) {
  const int id = static_cast<int>(boundaries_.size());
  check_edges(edges, msg("spring boundary ", id));
  if (!std::isfinite(p) || p <= 0) throw Error(msg("spring boundary ", id, ": stiffness p must be positive, got ", p));
  const int first = static_cast<int>(boundary_points_.size());
  for (const EdgeRef& e : edges) {
    const auto v = block_vertices(e.block);
    const Vec2 a = v[e.edge], b = v[(e.edge + 1) % v.size()];
    const double k = per_length ? p * (b - a).norm() : p;
    for (const Vec2& pt : {a, b})
      boundary_points_.push_back({id, e.block, pt, pt, Eigen::Matrix2d::Zero(), k, Vec2::Zero()});
  }
  boundaries_.push_back({BoundaryKind::Spring, first, static_cast<int>(boundary_points_.size()) - first});
  return id;
}

std::vector<Vec2> World::boundary_point_forces(int id) const {
  if (id < 0 || id >= static_cast<int>(boundaries_.size())) throw Error(msg("no boundary ", id));
  std::vector<Vec2> f;
  for (int i = 0; i < boundaries_[id].count; ++i) f.push_back(boundary_points_[boundaries_[id].first + i].force);
  return f;
}

Vec2 World::boundary_force(int id) const {
  Vec2 sum = Vec2::Zero();
  for (const Vec2& f : boundary_point_forces(id)) sum += f;
  return sum;
}

}  // namespace dda
