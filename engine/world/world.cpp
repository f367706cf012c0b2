#include "world/world.hpp"

#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "block/displacement.hpp"
#include "contact/broad_phase.hpp"
#include "contact/contact_law.hpp"
#include "contact/narrow_phase.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/polygon.hpp"
#include "solver/linear_solver.hpp"
#include "world/world_impl.hpp"

namespace dda {

World::World() : World(Controls{}) {}
World::World(const Controls& controls) : controls_(controls), impl_(std::make_unique<Impl>()) {
  joints_.push_back(JointMaterial{});
  vertex_start_.push_back(0);
}
World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

// ---- Model building ---------------------------------------------------------

int World::add_rock_material(const RockMaterial& m) {
  validate(m, static_cast<int>(rocks_.size()));
  rocks_.push_back(m);
  return static_cast<int>(rocks_.size()) - 1;
}

int World::add_joint_material(const JointMaterial& m) {
  validate(m, static_cast<int>(joints_.size()));
  joints_.push_back(m);
  return static_cast<int>(joints_.size()) - 1;
}

RockMaterial& World::rock_material(int id) {
  if (id < 0 || id >= rock_material_count()) throw Error(msg("no rock material ", id));
  return rocks_[id];
}

JointMaterial& World::joint_material(int id) {
  if (id < 0 || id >= joint_material_count()) throw Error(msg("no joint material ", id));
  return joints_[id];
}

BlockId World::check(BlockId b) const {
  if (b < 0 || static_cast<std::size_t>(b) >= block_count()) throw Error(msg("no block ", b));
  return b;
}

BlockId World::add_block(std::vector<Vec2> vertices, int rock_material, std::vector<int> edge_joints) {
  const BlockId id = static_cast<BlockId>(block_count());
  const std::string what = msg("block ", id);
  validate_simple_polygon(vertices, what);
  if (rock_material < 0 || rock_material >= rock_material_count())
    throw Error(msg(what, ": unknown rock material ", rock_material, " (", rock_material_count(), " defined)"));
  if (edge_joints.empty()) edge_joints.assign(vertices.size(), 0);
  if (edge_joints.size() != vertices.size())
    throw Error(msg(what, ": ", edge_joints.size(), " edge joints given for ", vertices.size(), " edges"));
  for (int j : edge_joints)
    if (j < 0 || j >= joint_material_count()) throw Error(msg(what, ": unknown joint material ", j));
  if (signed_area(vertices) < 0) {
    // Store counter-clockwise. Edge k (k → k+1) becomes edge n-2-k of the
    // reversed outline (indices mod n).
    const int n = static_cast<int>(vertices.size());
    std::reverse(vertices.begin(), vertices.end());
    std::vector<int> reversed(n);
    for (int k = 0; k < n; ++k) reversed[((n - 2 - k) % n + n) % n] = edge_joints[k];
    edge_joints = std::move(reversed);
  }
  const PolygonMoments m = polygon_moments(vertices);
  vertices_.insert(vertices_.end(), vertices.begin(), vertices.end());
  initial_vertices_.insert(initial_vertices_.end(), vertices.begin(), vertices.end());
  edge_joint_.insert(edge_joint_.end(), edge_joints.begin(), edge_joints.end());
  vertex_start_.push_back(static_cast<int>(vertices_.size()));
  centroid_.push_back(m.centroid);
  initial_centroid_.push_back(m.centroid);
  area_.push_back(m.area);
  sxx_.push_back(m.sxx);
  syy_.push_back(m.syy);
  sxy_.push_back(m.sxy);
  mass_.push_back(rocks_[rock_material].density * m.area);
  material_.push_back(rock_material);
  stress_.push_back(Vec3::Zero());
  velocity_.push_back(Vec6::Zero());
  last_displacement_.push_back(Vec6::Zero());
  prepared_ = false;
  return id;
}

void World::set_block_velocity(BlockId b, const Vec6& v) {
  if (!v.allFinite()) throw Error(msg("block ", b, ": velocity is not finite"));
  velocity_[check(b)] = v;
}

void World::set_block_stress(BlockId b, const Vec3& s) {
  if (!s.allFinite()) throw Error(msg("block ", b, ": stress is not finite"));
  stress_[check(b)] = s;
}

int World::add_point_load(BlockId b, const Vec2& point, const Vec2& force) {
  check(b);
  if (!point.allFinite()) throw Error(msg("point load on block ", b, ": point is not finite"));
  if (!force.allFinite()) throw Error(msg("point load on block ", b, ": force is not finite"));
  point_loads_.push_back({b, point, force});
  return static_cast<int>(point_loads_.size()) - 1;
}

void World::set_point_load(int id, const Vec2& force) {
  if (id < 0 || id >= static_cast<int>(point_loads_.size())) throw Error(msg("no point load ", id));
  if (!force.allFinite()) throw Error(msg("point load ", id, ": force is not finite"));
  point_loads_[id].force = force;
  // A fixed force replaces any force history the load had.
  std::erase_if(point_load_histories_, [&](const PointLoadHistory& h) { return h.load == id; });
}

int World::add_fixed_point(BlockId b, const Vec2& point) {
  check(b);
  if (!point.allFinite()) throw Error(msg("fixed point on block ", b, ": point is not finite"));
  fixed_points_.push_back({b, point, point});
  return static_cast<int>(fixed_points_.size()) - 1;
}

int World::add_tracked_point(BlockId b, const Vec2& point) {
  check(b);
  if (!point.allFinite()) throw Error(msg("tracked point on block ", b, ": point is not finite"));
  tracked_.push_back({b, point, point});
  return static_cast<int>(tracked_.size()) - 1;
}

Vec2 World::tracked_position(int id) const {
  if (id < 0 || id >= static_cast<int>(tracked_.size())) throw Error(msg("no tracked point ", id));
  return tracked_[id].point;
}
Vec2 World::tracked_displacement(int id) const { return tracked_position(id) - tracked_[id].origin; }
BlockId World::tracked_block(int id) const {
  tracked_position(id);
  return tracked_[id].block;
}

// ---- Read access ------------------------------------------------------------

std::span<const Vec2> World::block_vertices(BlockId b) const {
  check(b);
  return std::span<const Vec2>(vertices_).subspan(vertex_start_[b], vertex_start_[b + 1] - vertex_start_[b]);
}

std::span<const Vec2> World::block_initial_vertices(BlockId b) const {
  check(b);
  return std::span<const Vec2>(initial_vertices_).subspan(vertex_start_[b], vertex_start_[b + 1] - vertex_start_[b]);
}

int World::block_edge_joint(BlockId b, int edge) const {
  check(b);
  const int n = vertex_start_[b + 1] - vertex_start_[b];
  if (edge < 0 || edge >= n) throw Error(msg("block ", b, " has no edge ", edge));
  return edge_joint_[vertex_start_[b] + edge];
}

Vec2 World::velocity_at(BlockId b, const Vec2& p) const {
  check(b);
  return displacement_matrix(p, centroid_[b]) * velocity_[b];
}

double World::half_height() const {
  if (half_height_ > 0) return half_height_;
  double lo = INFINITY, hi = -INFINITY;
  for (const Vec2& v : vertices_) {
    lo = std::min(lo, v.y());
    hi = std::max(hi, v.y());
  }
  return vertices_.empty() ? 0 : 0.5 * (hi - lo);
}

double World::suggested_time_step() const {
  if (block_count() == 0) return 0;
  const BlockPolygons polys{vertex_start_, vertices_};
  double h_min = INFINITY, m_min = INFINITY, cp_max = 0, e_max = 0;
  for (std::size_t b = 0; b < block_count(); ++b) {
    double longest = 0;
    const auto v = polys.of(static_cast<int>(b));
    for (std::size_t k = 0; k < v.size(); ++k) longest = std::max(longest, (v[(k + 1) % v.size()] - v[k]).norm());
    h_min = std::min(h_min, area_[b] / longest);  // the block's height across its longest edge
    m_min = std::min(m_min, mass_[b]);
    cp_max = std::max(cp_max, p_wave_speed(rocks_[material_[b]], controls_.plane));
    e_max = std::max(e_max, rocks_[material_[b]].youngs);
  }
  const double g0 = controls_.g0 > 0 ? controls_.g0 : 50 * e_max;
  // Eqs. 1–3 with the paper's a = 0.05 and b = 0.177.
  return std::min(0.05 * h_min / cp_max, 2 * 0.177 * std::sqrt(m_min / g0));
}

const BlockSparseMatrix& World::last_matrix() const { return impl_->system.stored(); }
const VecX& World::last_rhs() const { return impl_->rhs; }

std::uint64_t World::state_hash() const {
  std::uint64_t h = 1469598103934665603ULL;
  auto mix = [&](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ULL;
  };
  mix(vertices_.data(), vertices_.size() * sizeof(Vec2));
  mix(velocity_.data(), velocity_.size() * sizeof(Vec6));
  mix(stress_.data(), stress_.size() * sizeof(Vec3));
  for (const Contact& c : contacts_) {
    mix(&c.vblock, sizeof c.vblock);
    mix(&c.vertex, sizeof c.vertex);
    mix(&c.eblock, sizeof c.eblock);
    mix(&c.edge, sizeof c.edge);
    mix(&c.state, sizeof c.state);
    mix(&c.intact, sizeof c.intact);
    mix(&c.normal_force, sizeof c.normal_force);
    mix(&c.shear_force, sizeof c.shear_force);
  }
  mix(&time_, sizeof time_);
  return h;
}

}  // namespace dda
