// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "world/world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "block/displacement.hpp"
#include "block/mesh.hpp"
#include "core/error.hpp"
#include "core/memory.hpp"
#include "geometry/polygon.hpp"
#include "loading/load_frequency.hpp"
#include "world/stepper.hpp"
#include "world/wave_model.hpp"

namespace dda {

World::World() : World(Controls{}) {}
World::World(const Controls& controls) : stepper_(std::make_unique<Stepper>()) {
  s_.controls = controls;
  s_.joints.push_back(JointMaterial{});
}
World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

StepStats World::step() {
  if (!s_.wave.decided) decide_wave_model();
  return stepper_->step(s_);
}

const WaveModel& World::decide_wave_model(std::span<const LoadSignal> script_signals) {
  if (s_.wave.decided) return s_.wave;
  if (s_.blocks.count() == 0) throw Error("the model has no blocks");
  WaveModel wave = choose_wave_model(s_, dynamic_load_frequency(s_, script_signals));
  const std::vector<double> sizes = meshes_for_waves(s_, wave.frequency);
  if (wave.meshed_blocks > 0) {
    s_.remeshing = mesh_in_place(s_.blocks, sizes, s_.rocks, s_.joints, s_.contact_spring());
    s_.remeshing.blocks = &s_.blocks;
    s_.loads.remesh(s_.remeshing);
    s_.boundaries.remesh(s_.remeshing, s_.rocks, s_.controls.plane);
    for (MaterialPoint& p : s_.tracked) p.block = s_.remeshing.element_at(p.block, p.origin);
    s_.remeshing.blocks = nullptr;
    s_.prepared = false;
  }
  s_.wave = std::move(wave);
  return s_.wave;
}

std::vector<EdgeRef> World::edges_since_meshing(EdgeRef e) const {
  if (s_.wave.meshed_blocks == 0) return {e};
  if (e.block < 0 || e.block + 1 >= static_cast<BlockId>(s_.remeshing.old_vertex_start.size()))
    throw Error(msg("no block ", e.block, " before the blocks were meshed"));
  const std::vector<int>& start = s_.remeshing.old_vertex_start;
  if (e.edge < 0 || e.edge >= start[e.block + 1] - start[e.block])
    throw Error(msg("block ", e.block, " had no edge ", e.edge, " before the blocks were meshed"));
  return s_.remeshing.edges({e});
}

std::vector<int> World::add_edge_targets(const std::vector<EdgeRef>& edges, bool directed, const Vec2& direction) {
  return s_.boundaries.add_edge_targets(s_.blocks, edges, directed, direction);
}

// ---- Model building ---------------------------------------------------------

int World::add_rock_material(const RockMaterial& m) {
  validate(m, static_cast<int>(s_.rocks.size()));
  s_.rocks.push_back(m);
  return static_cast<int>(s_.rocks.size()) - 1;
}

int World::add_joint_material(const JointMaterial& m) {
  validate(m, static_cast<int>(s_.joints.size()));
  s_.joints.push_back(m);
  return static_cast<int>(s_.joints.size()) - 1;
}

RockMaterial& World::rock_material(int id) {
  if (id < 0 || id >= rock_material_count()) throw Error(msg("no rock material ", id));
  return s_.rocks[id];
}

JointMaterial& World::joint_material(int id) {
  if (id < 0 || id >= joint_material_count()) throw Error(msg("no joint material ", id));
  return s_.joints[id];
}

const JointMaterial& World::joint_material(int id) const { return const_cast<World*>(this)->joint_material(id); }

BlockId World::check(BlockId b) const {
  if (b < 0 || static_cast<std::size_t>(b) >= block_count()) throw Error(msg("no block ", b));
  return b;
}

BlockId World::add_block(std::vector<Vec2> vertices, int rock_material, std::vector<int> edge_joints,
                         std::vector<EdgeTag> edge_tags) {
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
  if (edge_tags.empty()) edge_tags.assign(vertices.size(), EdgeTag{});
  if (edge_tags.size() != vertices.size())
    throw Error(msg(what, ": ", edge_tags.size(), " edge tags given for ", vertices.size(), " edges"));
  if (signed_area(vertices) < 0) {
    // Store counter-clockwise. Edge k (k → k+1) becomes edge n-2-k of the
    // reversed outline (indices mod n).
    const int n = static_cast<int>(vertices.size());
    std::reverse(vertices.begin(), vertices.end());
    auto reverse_edges = [n](auto& per_edge) {
      auto reversed = per_edge;
      for (int k = 0; k < n; ++k) reversed[((n - 2 - k) % n + n) % n] = per_edge[k];
      per_edge = std::move(reversed);
    };
    reverse_edges(edge_joints);
    reverse_edges(edge_tags);
  }
  double mesh_size = s_.rocks[rock_material].mesh_size > 0 ? s_.rocks[rock_material].mesh_size : s_.controls.mesh_size;
  // After the wave model meshed the blocks, a block added with an automatic
  // size gets the elements the load needs too.
  if (mesh_size < 0 && s_.wave.active && s_.wave.meshed_blocks > 0)
    mesh_size = wave_element_size(s_.rocks[rock_material], s_.wave.frequency);
  if (mesh_size > 0) return add_meshed_block(vertices, rock_material, edge_joints, edge_tags, mesh_size, what);
  return append_block(vertices, rock_material, edge_joints, edge_tags);
}

// A meshed block: each triangle of its mesh an element block, their corners
// numbered as shared nodes (block/mesh.hpp); edges on the outline keep the
// outline edge's joint material and tag.
BlockId World::add_meshed_block(const std::vector<Vec2>& outline, int rock_material,
                                const std::vector<int>& edge_joints, const std::vector<EdgeTag>& edge_tags,
                                double mesh_size, const std::string& what) {
  // Memory stated before the mesh is made (a tiny mesh_size makes millions of elements).
  const double elements = estimated_mesh_elements(outline, mesh_size);
  check_memory_need(kMeshBytesPerElement * elements, memory_headroom(), msg("meshing ", what),
                    msg("about ", std::round(elements), " elements at mesh_size ", mesh_size, " m"),
                    "give a larger mesh_size (the rock's mesh_size, or the model's mesh_size control)");
  const TriangleMesh mesh = mesh_polygon(outline, mesh_size, what);
  Blocks& bl = s_.blocks;
  const int first_node = mesh_node_count(bl);
  int mesh_id = 0;
  for (const int m : bl.mesh) mesh_id = std::max(mesh_id, m + 1);
  const BlockId first = static_cast<BlockId>(block_count());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    std::vector<Vec2> corners(3);
    std::vector<int> joints(3, 0);
    std::vector<EdgeTag> tags(3);
    for (int k = 0; k < 3; ++k) {
      corners[k] = mesh.nodes[mesh.triangles[t][k]];
      const int edge = mesh.outline_edge[t][k];
      if (edge >= 0) joints[k] = edge_joints[edge], tags[k] = edge_tags[edge];
    }
    const BlockId e = append_block(corners, rock_material, joints, tags);
    const int start = bl.vertex_start[e];
    bl.mesh[e] = mesh_id;
    for (int k = 0; k < 3; ++k) {
      bl.node[start + k] = first_node + mesh.triangles[t][k];
      bl.inner_edge[start + k] = mesh.outline_edge[t][k] < 0;
    }
  }
  return first;
}

// Appends a counter-clockwise polygon, checked, as a first-order block.
BlockId World::append_block(const std::vector<Vec2>& vertices, int rock_material, const std::vector<int>& edge_joints,
                            const std::vector<EdgeTag>& edge_tags) {
  s_.prepared = false;
  return dda::append_block(s_.blocks, vertices, rock_material, s_.rocks[rock_material].density, edge_joints, edge_tags,
                           s_.rocks[rock_material].mesh_size > 0 || s_.controls.mesh_size > 0);
}

// An element of a meshed block stands for its whole block: the rates are
// taken about the mesh's centroid and each element gets them about its own
// (block/mesh.hpp), so the block moves as one body.
void World::set_block_velocity(BlockId b, const Vec6& v) {
  if (!v.allFinite()) throw Error(msg("block ", b, ": velocity is not finite"));
  Blocks& bl = s_.blocks;
  if (!bl.is_element(check(b))) {
    bl.velocity[b] = v;
    return;
  }
  const Vec2 c = mesh_centroid(bl, bl.mesh[b]);
  for (std::size_t e = 0; e < bl.count(); ++e)
    if (bl.mesh[e] == bl.mesh[b]) {
      bl.velocity[e] = v;
      bl.velocity[e].head<2>() = displacement_matrix(bl.centroid[e], c) * v;
    }
}

void World::set_block_stress(BlockId b, const Vec3& s) {
  if (!s.allFinite()) throw Error(msg("block ", b, ": stress is not finite"));
  Blocks& bl = s_.blocks;
  bl.stress[check(b)] = s;
  if (bl.is_element(b))
    for (std::size_t e = 0; e < bl.count(); ++e)
      if (bl.mesh[e] == bl.mesh[b]) bl.stress[e] = s;
}

int World::add_point_load(BlockId b, const Vec2& point, const Vec2& force) {
  check(b);
  return s_.loads.add_point_load(element_under(s_.blocks, b, point), point, force);
}
void World::set_point_load(int id, const Vec2& force) { s_.loads.set_point_load(id, force); }

int World::add_fixed_point(BlockId b, const Vec2& point) {
  check(b);
  return s_.boundaries.add_fixed_point(element_under(s_.blocks, b, point), point);
}

int World::add_tracked_point(BlockId b, const Vec2& point) {
  check(b);
  if (!point.allFinite()) throw Error(msg("tracked point on block ", b, ": point is not finite"));
  s_.tracked.push_back({element_under(s_.blocks, b, point), point, point});
  return static_cast<int>(s_.tracked.size()) - 1;
}

Vec2 World::tracked_position(int id) const {
  if (id < 0 || id >= static_cast<int>(s_.tracked.size())) throw Error(msg("no tracked point ", id));
  return s_.tracked[id].point;
}
Vec2 World::tracked_displacement(int id) const { return tracked_position(id) - s_.tracked[id].origin; }
BlockId World::tracked_block(int id) const {
  tracked_position(id);
  return s_.tracked[id].block;
}

// ---- Loads and boundaries on edges ---------------------------------------------

int World::add_pressure_load(const std::vector<EdgeRef>& edges, double pressure) {
  return s_.loads.add_pressure_load(s_.blocks, edges, pressure);
}
void World::set_pressure(int id, double pressure) { s_.loads.set_pressure(id, pressure); }
void World::set_pressure_history(int id, History pressure) { s_.loads.set_pressure_history(id, std::move(pressure)); }
void World::set_point_load_history(int id, const Vec2& direction, History magnitude) {
  s_.loads.set_point_load_history(id, direction, std::move(magnitude));
}

int World::add_displacement_target(BlockId b, const Vec2& point, const Vec2& direction) {
  return s_.boundaries.add_displacement_target(s_.blocks, element_under(s_.blocks, check(b), point), point, direction);
}
void World::set_target_displacement(int id, const Vec2& target) { s_.boundaries.set_target_displacement(id, target); }
void World::set_target_history(int id, History displacement) {
  s_.boundaries.set_target_history(id, std::move(displacement));
}
void World::set_target_velocity_history(int id, History velocity) {
  s_.boundaries.set_target_velocity_history(id, std::move(velocity));
}

void World::set_target_acceleration_history(int id, History acceleration) {
  s_.boundaries.set_target_acceleration_history(id, std::move(acceleration));
}
Vec2 World::target_point_displacement(int id) const { return s_.boundaries.target_point_displacement(id); }
Vec2 World::target_value(int id) const { return s_.boundaries.target_value(id); }

void World::fix_edges(const std::vector<EdgeRef>& edges) { s_.boundaries.fix_edges(s_.blocks, edges); }
int World::add_viscous_boundary(const std::vector<EdgeRef>& edges, int medium) {
  if (medium >= static_cast<int>(s_.rocks.size()))
    throw Error(msg("viscous boundary: no rock material ", medium, " (there are ", s_.rocks.size(), ")"));
  return s_.boundaries.add_viscous_boundary(s_.blocks, s_.rocks, edges, medium);
}

void World::set_incident_velocity(int boundary, History vx, History vy) {
  s_.boundaries.set_incident_velocity(boundary, std::move(vx), std::move(vy));
}

int World::add_free_field(const std::vector<EdgeRef>& side, int base) {
  return s_.boundaries.add_free_field(s_.blocks, s_.rocks, s_.controls.plane, side, base);
}

Vec2 World::free_field_velocity(int boundary, double y) const { return s_.boundaries.free_field_velocity(boundary, y); }

int World::add_spring_boundary(const std::vector<EdgeRef>& edges, double p, bool per_length) {
  return s_.boundaries.add_spring_boundary(s_.blocks, edges, p, per_length);
}
std::vector<Vec2> World::boundary_point_forces(int id) const { return s_.boundaries.boundary_point_forces(id); }

Vec2 World::boundary_force(int id) const {
  Vec2 sum = Vec2::Zero();
  for (const Vec2& f : boundary_point_forces(id)) sum += f;
  return sum;
}

// ---- Read access ------------------------------------------------------------

std::span<const Vec2> World::block_vertices(BlockId b) const { return s_.blocks.outline(check(b)); }

std::span<const Vec2> World::block_initial_vertices(BlockId b) const {
  check(b);
  return std::span<const Vec2>(s_.blocks.initial_vertices)
      .subspan(s_.blocks.vertex_start[b], s_.blocks.vertex_count(b));
}

int World::block_edge_joint(BlockId b, int edge) const {
  check(b);
  const int n = s_.blocks.vertex_count(b);
  if (edge < 0 || edge >= n) throw Error(msg("block ", b, " has no edge ", edge));
  return s_.blocks.edge_joint[s_.blocks.vertex_start[b] + edge];
}

const EdgeTag& World::block_edge_tag(BlockId b, int edge) const {
  block_edge_joint(b, edge);  // checks both
  return s_.blocks.edge_tag[s_.blocks.vertex_start[b] + edge];
}

Vec2 World::velocity_at(BlockId b, const Vec2& p) const {
  check(b);
  return displacement_matrix(p, s_.blocks.centroid[b]) * s_.blocks.velocity[b];
}

double World::half_height() const { return s_.half_height > 0 ? s_.half_height : s_.measured_half_height(); }

const BlockSparseMatrix& World::last_matrix() const { return stepper_->system().stored(); }
const VecX& World::last_rhs() const { return stepper_->rhs(); }
const ContactModel* World::contact_model() const { return stepper_->current_contact_model(); }

std::uint64_t World::state_hash() const {
  std::uint64_t h = 1469598103934665603ULL;
  auto mix = [&](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ULL;
  };
  const Blocks& bl = s_.blocks;
  mix(bl.vertices.data(), bl.vertices.size() * sizeof(Vec2));
  mix(bl.velocity.data(), bl.velocity.size() * sizeof(Vec6));
  mix(bl.stress.data(), bl.stress.size() * sizeof(Vec3));
  for (const Contact& c : s_.contacts) {
    mix(&c.vblock, sizeof c.vblock);
    mix(&c.vertex, sizeof c.vertex);
    mix(&c.eblock, sizeof c.eblock);
    mix(&c.edge, sizeof c.edge);
    mix(&c.state, sizeof c.state);
    mix(&c.intact, sizeof c.intact);
    mix(&c.normal_force, sizeof c.normal_force);
    mix(&c.shear_force, sizeof c.shear_force);
  }
  mix(&s_.time, sizeof s_.time);
  return h;
}

}  // namespace dda
