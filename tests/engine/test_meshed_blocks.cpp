// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Meshed (deformable) blocks (block/mesh.hpp, assembly/mesh_reduction.hpp,
// docs/meshed_blocks.md): the mesher, rigid motion, contacts on the outline,
// determinism, and the 1-D wave equation in one meshed block.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "../scenes.hpp"
#include "block/mesh.hpp"
#include "core/error.hpp"
#include "geometry/cutting.hpp"
#include "geometry/polygon.hpp"
#include "world/cut_blocks.hpp"

using namespace dda;

namespace {

// Every triangle counter-clockwise; the areas add up to the polygon's; an
// edge inside appears twice, in opposite directions, and an outline edge
// once (conforming, no hanging node); no edge longer than `longest`.
void expect_conforming_cover(const TriangleMesh& mesh, const std::vector<Vec2>& outline, double longest) {
  double area = 0;
  std::map<std::pair<int, int>, int> edges;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const double a = signed_area(std::vector<Vec2>{mesh.nodes[tri[0]], mesh.nodes[tri[1]], mesh.nodes[tri[2]]});
    EXPECT_GT(a, 0);
    area += a;
    for (int k = 0; k < 3; ++k) {
      ++edges[{tri[k], tri[(k + 1) % 3]}];
      const double length = (mesh.nodes[tri[(k + 1) % 3]] - mesh.nodes[tri[k]]).norm();
      EXPECT_LE(length, longest);
    }
  }
  EXPECT_NEAR(area, signed_area(outline), 1e-12 * signed_area(outline));
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      const bool twin = edges.count({b, a}) > 0;
      EXPECT_EQ(edges[std::make_pair(a, b)], 1);
      EXPECT_EQ(twin, mesh.outline_edge[t][k] < 0) << "edge " << a << "-" << b;
    }
}

void expect_conforming_cover(const std::vector<Vec2>& outline, double size) {
  expect_conforming_cover(mesh_convex_polygon(outline, size, "test block"), outline, 1.5 * size);
}

TEST(MeshedBlocks, MesherCoversConvexPolygonsConformingly) {
  expect_conforming_cover(test::rectangle(0, 0, 1, 0.5), 0.1);
  expect_conforming_cover({{0, 0}, {1, 0.2}, {0.8, 1.1}, {-0.1, 0.7}}, 0.15);  // a general quadrilateral
  expect_conforming_cover({{0, 0}, {1, 0}, {0.3, 0.8}}, 0.2);
  expect_conforming_cover({{0, 0}, {1, 0}, {1.4, 0.6}, {0.5, 1.2}, {-0.3, 0.6}}, 0.2);  // a pentagon: the fan
  const TriangleMesh square = mesh_convex_polygon(test::rectangle(0, 0, 1, 1), 0.25, "square");
  EXPECT_EQ(square.triangles.size(), 64u);  // 4 × 4 cells, four triangles about each centre
  EXPECT_EQ(square.nodes.size(), 41u);      // 25 corners, 16 centres
}

TEST(MeshedBlocks, AMeshTooFineIsRefusedBeforeItIsMade) {
  for (const auto& outline :
       {test::rectangle(0, 0, 100, 100), std::vector<Vec2>{{0, 0}, {100, 0}, {100, 100}, {50, 1}, {0, 100}}})
    try {
      mesh_polygon(outline, 1e-3, "block 7");
      FAIL() << "10^10 elements were asked for";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("use a larger mesh size"), std::string::npos) << e.what();
    }
}

// Concave outlines (block/mesh_cgal.cpp, CGAL's Delaunay refinement).
const std::vector<Vec2> kLShape{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
// The rock around half a tunnel: a 4 × 3 m block with a half-octagon notch
// of radius 1 m cut from the middle of its base (as a joint cut through a
// hole leaves it).
std::vector<Vec2> notched_block() {
  std::vector<Vec2> v{{-2, 0}, {-1, 0}};
  for (int k = 7; k >= 1; --k) v.push_back({std::cos(M_PI * k / 8), std::sin(M_PI * k / 8)});
  for (Vec2 p : {Vec2(1, 0), Vec2(2, 0), Vec2(2, 3), Vec2(-2, 3)}) v.push_back(p);
  return v;
}

// Reference: the mesher's contract (mesh.hpp). Conforming cover of the
// outline; every edge within the mesh size; every angle at least
// asin(sqrt(kConcaveMeshShapeBound)) = 20.7° (the outlines have no corner
// sharper than that; 1e-9 rad for the round-off of the angles' computation);
// every outline vertex a node, and the outline cut at the mesh size.
TEST(MeshedBlocks, ConcaveMesherHonoursItsSizeAndAngleBounds) {
  const double min_angle = std::asin(std::sqrt(kConcaveMeshShapeBound));
  for (const auto& [outline, size] : {std::pair{kLShape, 0.25}, {notched_block(), 0.3}, {kLShape, 0.07}}) {
    const TriangleMesh mesh = mesh_polygon(outline, size, "concave block");
    expect_conforming_cover(mesh, outline, size * (1 + 1e-12));
    double smallest = M_PI;
    for (const auto& tri : mesh.triangles)
      for (int k = 0; k < 3; ++k) {
        const Vec2 a = mesh.nodes[tri[(k + 1) % 3]] - mesh.nodes[tri[k]];
        const Vec2 b = mesh.nodes[tri[(k + 2) % 3]] - mesh.nodes[tri[k]];
        smallest = std::min(smallest, std::atan2(cross(a, b), a.dot(b)));
      }
    EXPECT_GE(smallest, min_angle - 1e-9) << "size " << size;
    for (const Vec2& corner : outline)
      EXPECT_TRUE(std::any_of(mesh.nodes.begin(), mesh.nodes.end(), [&](const Vec2& p) { return p == corner; }));
    std::printf("concave mesh at %.2f m: %zu elements, %zu nodes, smallest angle %.2f deg\n", size,
                mesh.triangles.size(), mesh.nodes.size(), smallest * 180 / M_PI);
  }
}

// Same outline, same mesh to the bit: CGAL's refinement is sequential, its
// point location walks with a fixed seed and its queues order faces by
// their points, not their addresses; the nodes and triangles are then
// numbered from the geometry alone. The second mesh is made on a heap
// churned in between (CGAL's storage at other addresses), for the notched
// block and for an L with a 2° spike (CGAL's clusters of small angles, kept
// in maps keyed by vertex address).
TEST(MeshedBlocks, ConcaveMeshIsTheSameEveryTime) {
  const double spike = std::tan(2 * M_PI / 180);
  const std::vector<Vec2> spiked{{0, 0}, {2, 0}, {2, 0.5 - spike}, {3, 0.5}, {2, 0.5}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  for (const auto& outline : {notched_block(), spiked}) {
    const TriangleMesh a = mesh_polygon(outline, 0.2, "a");
    std::vector<std::vector<char>> churn;
    for (int i = 0; i < 2000; ++i) churn.emplace_back(1 + (i * 7919) % 4096);
    for (std::size_t i = 0; i < churn.size(); i += 2) churn[i] = std::vector<char>();  // frees it
    const TriangleMesh b = mesh_polygon(outline, 0.2, "b");
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    for (std::size_t i = 0; i < a.nodes.size(); ++i) EXPECT_TRUE(a.nodes[i] == b.nodes[i]) << i;
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.outline_edge, b.outline_edge);
  }
}

TEST(MeshedBlocks, AnOutlineThatCrossesItselfIsRefusedWithTheCause) {
  const std::vector<Vec2> bow_tie{{0, 0}, {1, 1}, {1, 0}, {0, 1}};
  try {
    mesh_concave_polygon(bow_tie, 0.1, "block 3");
    FAIL() << "a bow tie was meshed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("block 3: its outline crosses or touches itself"), std::string::npos)
        << e.what();
  }
  World w;  // through the model, the polygon check speaks first
  RockMaterial rock = test::granite();
  rock.mesh_size = 0.1;
  const int r = w.add_rock_material(rock);
  EXPECT_THROW(w.add_block(bow_tie, r), Error);
}

// A block cannot have a hole (one outline per block): the cutter cuts the
// rock around an excavation free with two joints (inner_cut_material), and
// the two concave blocks are meshed by CGAL. Reference: the elements tile
// the domain minus the hole (area to 1e-12), and the element edges tagged
// with the hole run its whole perimeter (to 1e-12): the excavation's
// boundary is the meshes' outline, where its loads and contacts act.
// A 6 × 4 m domain with an octagonal hole of radius 1 m at its centre, cut
// free by inner_cut_material into two concave blocks.
std::vector<Vec2> excavation_hole() {
  std::vector<Vec2> hole;
  for (int k = 0; k < 8; ++k) hole.push_back(Vec2(3, 2) + Vec2(std::cos(M_PI * k / 4), std::sin(M_PI * k / 4)));
  return hole;
}
geometry::BlockSet excavation_blocks() {
  geometry::CutInput in;
  in.domain = test::rectangle(0, 0, 6, 4);
  in.holes = {excavation_hole()};
  in.inner_cut_material = 0;
  return geometry::cut_blocks(in);
}

TEST(MeshedBlocks, RockAroundAnExcavationIsMeshedAsConcaveBlocks) {
  const geometry::BlockSet set = excavation_blocks();
  ASSERT_EQ(set.blocks.size(), 2u);
  Controls c;
  c.mesh_size = 0.3;
  World w(c);
  w.add_rock_material(test::granite());
  const std::vector<BlockId> elements = add_cut_blocks(w, set, {});
  double area = 0, hole_edges = 0;
  for (const BlockId e : elements) {
    area += w.block_area(e);
    const auto v = w.block_vertices(e);
    for (int k = 0; k < 3; ++k)
      if (w.block_edge_tag(e, k).kind == EdgeKind::Hole) hole_edges += (v[(k + 1) % 3] - v[k]).norm();
  }
  const std::vector<Vec2> hole = excavation_hole();
  EXPECT_NEAR(area, 24 - signed_area(hole), 1e-12 * 24);
  EXPECT_NEAR(hole_edges, 8 * (hole[1] - hole[0]).norm(), 1e-12 * 8);
  std::printf("rock around the excavation: %zu elements\n", elements.size());
}

// The two meshed halves of the excavated rock on a fixed base under gravity
// (static, gg = 0; Δt = 1e-2 s, at which 30 steps settle the loads to 1e-9):
// the upper half rests on the lower one along the two cut joints, outline
// to outline of two CGAL meshes, and the lower one on the base. Reference:
// the base carries the weight of both and the cut joints the upper half's,
// m·g within 1e-6 each.
TEST(MeshedBlocks, TwoConcaveMeshesRestOnEachOtherAndOnTheBase) {
  Controls c;
  c.gravity = {0, -9.81};
  c.gg = 0;
  c.g1 = 1e-2;
  World w(c);
  RockMaterial meshed = test::granite();
  meshed.mesh_size = 0.5;
  w.add_rock_material(meshed);  // material 0: the cut blocks'
  const BlockId base = test::add_fixed_base(w, test::rectangle(-1, -1, 8, 1), w.add_rock_material(test::granite()));
  const std::vector<BlockId> elements = add_cut_blocks(w, excavation_blocks(), {});
  for (int i = 0; i < 30; ++i) w.step();
  double weight = 0, upper = 0, on_base = 0, between = 0;
  for (const BlockId e : elements) {
    weight += w.block_mass(e) * 9.81;
    if (w.block_centroid(e).y() > 2) upper += w.block_mass(e) * 9.81;
  }
  for (const Contact& k : w.contacts()) (k.vblock == base || k.eblock == base ? on_base : between) += k.normal_force;
  EXPECT_NEAR(on_base, weight, 1e-6 * weight);
  EXPECT_NEAR(between, upper, 1e-6 * upper);
}

// The patch test (Irons): an L-shaped meshed block loaded on its outline by
// the nodal forces of a uniform stress σ (each outline segment's σ·n·L, half
// to each end), held by three restraints only (a fixed point, and a point
// held in y on the same level), which carry nothing in equilibrium. Exact
// answer: every element carries σ. Static analysis (gg = 0) with Δt = 1 s, so
// the inertia of a step weighs ρL²/(EΔt²) = 2e-6 of the stiffness and three
// steps take it out (one step leaves 6e-5); the moved geometry (each step
// solves on the outline the last one left) changes the answer by a few times
// the strain, 2e-8 at σ of 100 Pa: the error is 7.5e-8 of |σ|, and grows in
// proportion to σ. Tolerance: 1e-6 of |σ|.
TEST(MeshedBlocks, ConcaveMeshedBlockPassesThePatchTest) {
  Controls c;
  c.gg = 0;
  c.g1 = 1;
  c.mesh_size = 0.25;
  World w(c);
  const int r = w.add_rock_material(test::granite());
  const BlockId first = w.add_block(kLShape, r);
  const Vec3 sigma(100, -60, 40);                                     // σxx, σyy, τxy (tension +)
  const TriangleMesh mesh = mesh_polygon(kLShape, c.mesh_size, "L");  // the same mesh as the block's
  ASSERT_EQ(w.block_count() - first, mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      if (mesh.outline_edge[t][k] < 0) continue;
      const Vec2 p = mesh.nodes[mesh.triangles[t][k]], q = mesh.nodes[mesh.triangles[t][(k + 1) % 3]];
      const Vec2 nl(q.y() - p.y(), p.x() - q.x());  // outward normal × length (counter-clockwise outline)
      const Vec2 half(0.5 * (sigma[0] * nl.x() + sigma[2] * nl.y()), 0.5 * (sigma[2] * nl.x() + sigma[1] * nl.y()));
      w.add_point_load(first, p, half);
      w.add_point_load(first, q, half);
    }
  w.add_fixed_point(first, {0, 0});
  const int held = w.add_displacement_target(first, {2, 0}, {0, 1});
  w.set_target_displacement(held, {0, 0});
  for (int i = 0; i < 3; ++i) w.step();
  double worst = 0;
  for (std::size_t b = first; b < w.block_count(); ++b)
    worst = std::max(worst, (w.block_stress(static_cast<BlockId>(b)) - sigma).norm() / sigma.norm());
  std::printf("patch test: largest relative stress error %.3g\n", worst);
  EXPECT_LT(worst, 1e-6);
}

// Free fall is exact under Shi's scheme (constant acceleration): every node
// of a meshed block falls ½gt² (to 1e-9), and the elements stay unstrained:
// under 1e-2 Pa, what the solves' relative residual (1e-10) leaves, against
// the 1.3e4 Pa its weight would make if it were held.
TEST(MeshedBlocks, MeshedBlockFallsFreelyAsOneBody) {
  Controls c;
  c.gravity = {0, -9.81};
  c.g1 = 1e-3;
  c.mesh_size = 0.25;
  World w(c);
  const int r = w.add_rock_material(test::granite());
  w.add_block(test::rectangle(0, 0, 1, 0.5), r);
  ASSERT_EQ(w.block_count(), 32u);
  std::vector<Vec2> start;
  for (std::size_t b = 0; b < w.block_count(); ++b)
    for (const Vec2& v : w.block_vertices(static_cast<BlockId>(b))) start.push_back(v);
  for (int i = 0; i < 100; ++i) w.step();
  const double t = w.time(), fall = 0.5 * 9.81 * t * t;
  std::size_t k = 0;
  for (std::size_t b = 0; b < w.block_count(); ++b) {
    for (const Vec2& v : w.block_vertices(static_cast<BlockId>(b))) {
      EXPECT_NEAR(v.x(), start[k].x(), 1e-12);
      EXPECT_NEAR(v.y(), start[k].y() - fall, 1e-9 * fall);
      ++k;
    }
    EXPECT_LT(w.block_stress(static_cast<BlockId>(b)).norm(), 1e-2);
  }
  EXPECT_TRUE(w.contacts().empty());  // elements of one mesh never contact each other
}

// A small L-shaped (concave) block, meshed by CGAL at 0.25 m.
const std::vector<Vec2> kSmallL{{0, 0}, {1, 0}, {1, 0.5}, {0.5, 0.5}, {0.5, 1}, {0, 1}};

// A drift and a spin given to an element are the meshed block's: every
// element takes the rates about the block's centroid, and the block moves as
// one body, a convex one (structured mesh) and a concave one (CGAL's).
// Reference: rigid motion, translation by vt and rotation by ωt about the
// centroid; the linearised motion of the elements' corners leaves (ωt)²/2 of
// the radius per step at most (tolerance 1e-7 m at ωt = 2e-3 over 20 steps,
// radius under 0.8 m). A drift strains nothing: every element's stress stays
// under 1e-3 Pa (measured 4e-5, what the solves' relative residual leaves).
// A spinning body carries its centripetal stress, of order ρω²R² (R the
// farthest corner from the centroid; a disc's largest is 0.41ρω²R²): 3 and
// 9 Pa measured against 8 and 13 Pa, where a rotation taken as strain would
// leave E(ωΔt)²/2 a step, 500 Pa over the run.
TEST(MeshedBlocks, DriftAndSpinSetOnOneElementMoveTheWholeBlock) {
  for (const auto& outline : {test::rectangle(0, 0, 1, 0.5), kSmallL})
    for (const double omega : {0.0, 0.1}) {
      Controls c;
      c.g1 = 1e-3;
      c.mesh_size = 0.25;
      World w(c);
      const RockMaterial rock = test::granite();
      const BlockId first = w.add_block(outline, w.add_rock_material(rock));
      const Vec2 drift(0.3, -0.2);
      w.set_block_velocity(first + 5, Vec6(drift.x(), drift.y(), omega, 0, 0, 0));
      std::vector<Vec2> start;
      for (std::size_t b = 0; b < w.block_count(); ++b)
        for (const Vec2& v : w.block_vertices(static_cast<BlockId>(b))) start.push_back(v);
      for (int i = 0; i < 20; ++i) w.step();
      const double angle = omega * w.time();
      const Vec2 centre = polygon_moments(outline).centroid;
      double radius = 0;
      for (const Vec2& v : outline) radius = std::max(radius, (v - centre).norm());
      const double stress_bound = omega > 0 ? rock.density * omega * omega * radius * radius : 1e-3;
      std::size_t k = 0;
      for (std::size_t b = 0; b < w.block_count(); ++b) {
        for (const Vec2& v : w.block_vertices(static_cast<BlockId>(b))) {
          const Vec2 p = start[k++] - centre;
          const Vec2 moved = centre + drift * w.time() +
                             Vec2(std::cos(angle) * p.x() - std::sin(angle) * p.y(),
                                  std::sin(angle) * p.x() + std::cos(angle) * p.y());
          EXPECT_NEAR((v - moved).norm(), 0, 1e-7);
        }
        EXPECT_LT(w.block_stress(static_cast<BlockId>(b)).norm(), stress_bound) << "element " << b;
      }
    }
}

// The elements' mass (MeshMass) under rigid motion of a free 1 m × 0.5 m
// block meshed at 0.25 m (32 elements), from the kinetic energy after one
// `newmark` step (the solve's tolerance, 1e-10, bounds the error; tolerance
// 1e-8 relative). Reference: translation, ½·m·v² under every mass (a lumped
// mass keeps the mass and its centre); rotation about the centroid, ½·J·ω²
// with J = ρ·ab(a² + b²)/12 (consistent: exact), J = Σ (ρA_e/3)·|pᵢ − c|² over
// every element's corners (lumped: the nodes' masses), their mean (mixed).
// And free fall under Shi's scheme: ½gt² for every node under every mass.
TEST(MeshedBlocks, EveryMeshMassKeepsTheMassAndTranslationExact) {
  const RockMaterial rock = test::granite();
  const double a = 1, b = 0.5, mass = rock.density * a * b;
  const Vec2 centre(0.5, 0.25);
  for (const MeshMass kind : {MeshMass::Consistent, MeshMass::Lumped, MeshMass::Mixed}) {
    Controls c;
    c.integrator = Integrator::Newmark;
    c.g1 = 1e-4;
    c.mesh_size = 0.25;
    c.mesh_mass = kind;
    World spin(c), slide(c);
    const BlockId first = spin.add_block(test::rectangle(0, 0, a, b), spin.add_rock_material(rock));
    slide.add_block(test::rectangle(0, 0, a, b), slide.add_rock_material(rock));
    double corner_j = 0;
    for (std::size_t e = first; e < spin.block_count(); ++e) {
      const auto v = spin.block_vertices(static_cast<BlockId>(e));
      const double area = 0.5 * std::abs((v[1] - v[0]).x() * (v[2] - v[0]).y() - (v[1] - v[0]).y() * (v[2] - v[0]).x());
      for (const Vec2& p : v) corner_j += rock.density * area / 3 * (p - centre).squaredNorm();
    }
    const double exact_j = mass * (a * a + b * b) / 12;
    const double j = kind == MeshMass::Consistent ? exact_j
                     : kind == MeshMass::Lumped   ? corner_j
                                                  : 0.5 * (exact_j + corner_j);
    const double omega = 0.1;
    spin.set_block_velocity(first + 5, Vec6(0, 0, omega, 0, 0, 0));
    slide.set_block_velocity(first + 5, Vec6(1, 0.5, 0, 0, 0, 0));
    spin.step();
    slide.step();
    std::printf("mass %d: J / J_exact = %.4f\n", static_cast<int>(kind), j / exact_j);
    EXPECT_NEAR(spin.energy().total.kinetic, 0.5 * j * omega * omega, 1e-8 * 0.5 * j * omega * omega);
    EXPECT_NEAR(slide.energy().total.kinetic, 0.5 * mass * 1.25, 1e-8 * 0.5 * mass * 1.25);

    c.integrator = Integrator::Shi;
    c.gravity = {0, -9.81};
    c.g1 = 1e-3;
    World fall(c);
    fall.add_block(test::rectangle(0, 0, a, b), fall.add_rock_material(rock));
    std::vector<Vec2> start;
    for (std::size_t e = 0; e < fall.block_count(); ++e)
      for (const Vec2& v : fall.block_vertices(static_cast<BlockId>(e))) start.push_back(v);
    for (int i = 0; i < 100; ++i) fall.step();
    const double drop = 0.5 * 9.81 * fall.time() * fall.time();
    std::size_t k = 0;
    for (std::size_t e = 0; e < fall.block_count(); ++e)
      for (const Vec2& v : fall.block_vertices(static_cast<BlockId>(e))) {
        EXPECT_NEAR(v.x(), start[k].x(), 1e-12);
        EXPECT_NEAR(v.y(), start[k].y() - drop, 1e-9 * drop);
        ++k;
      }
  }
}

// A static analysis (gg = 0, Δt = 1 ms) under gravity, for the resting tests.
World static_world_under_gravity() {
  Controls c;
  c.gravity = {0, -9.81};
  c.gg = 0;
  c.g1 = 1e-3;
  return World(c);
}

// Granite whose blocks are meshed at `size`; returns the material's index.
int add_meshed_granite(World& w, double size) {
  RockMaterial meshed = test::granite();
  meshed.mesh_size = size;
  return w.add_rock_material(meshed);
}

// A meshed block resting on a fixed first-order base (static analysis,
// gg = 0), a square (structured mesh) and an L (CGAL's mesh): contacts only
// on the outline nodes, their normal forces carry the block's weight
// (reference: m·g, within 1e-6).
TEST(MeshedBlocks, MeshedBlockRestsOnItsOutlineContacts) {
  for (const auto& outline : {test::rectangle(0, 0, 1, 1), kSmallL}) {
    World w = static_world_under_gravity();
    const int base_rock = w.add_rock_material(test::granite());
    const int r = add_meshed_granite(w, 0.25);
    test::add_fixed_base(w, test::rectangle(-1, -1, 3, 1), base_rock);
    const BlockId first = w.add_block(outline, r);
    for (int i = 0; i < 30; ++i) w.step();
    double weight = 0;
    for (std::size_t b = first; b < w.block_count(); ++b) weight += w.block_mass(static_cast<BlockId>(b)) * 9.81;
    double normal = 0;
    for (const Contact& k : w.contacts()) {
      const bool on_mesh = k.vblock >= first || k.eblock >= first;
      ASSERT_TRUE(on_mesh);  // no contact inside the mesh
      normal += k.normal_force;
      // The element side of the contact is an outline edge or outline node of the mesh.
      const BlockId element = k.vblock >= first ? k.vblock : k.eblock;
      bool on_bottom = false;
      // (The base and the block compress by micrometres; the next row of nodes is 0.25 m up.)
      for (const Vec2& v : w.block_vertices(element)) on_bottom = on_bottom || std::abs(v.y()) < 1e-3;
      EXPECT_TRUE(on_bottom) << "contact " << k.vblock << ":" << k.vertex << " on " << k.eblock << ":" << k.edge
                             << " state " << int(k.state);
    }
    EXPECT_NEAR(normal, weight, 1e-6 * weight) << outline.size() << " corners";
  }
}

// A first-order block nestled in the inner corner of a meshed L (static,
// gg = 0), the L on a fixed base: the square rests on the L's step and
// against its wall, its corner at the reflex corner of the L's outline.
// Reference: the base carries the weight of both (the square's through the
// L's mesh), m·g within 1e-6; the square touches step and wall, and settles
// by the contacts' penetration only (under 1e-5 m).
TEST(MeshedBlocks, BlockInTheInnerCornerOfAMeshedLRestsOnIt) {
  World w = static_world_under_gravity();
  const int rock = w.add_rock_material(test::granite());
  const int r = add_meshed_granite(w, 0.25);
  const BlockId base = test::add_fixed_base(w, test::rectangle(-1, -1, 3, 1), rock);
  const BlockId first = w.add_block(kSmallL, r);
  const BlockId square = w.add_block(test::rectangle(0.5, 0.5, 0.3, 0.3), rock);
  const Vec2 start = w.block_centroid(square);
  for (int i = 0; i < 40; ++i) w.step();
  double weight = 0;
  for (std::size_t b = first; b < w.block_count(); ++b) weight += w.block_mass(static_cast<BlockId>(b)) * 9.81;
  double on_base = 0;
  bool on_step = false, on_wall = false;
  for (const Contact& k : w.contacts()) {
    if (k.vblock == base || k.eblock == base) on_base += k.normal_force;
    if ((k.vblock == square || k.eblock == square) && k.normal_force > 0) {
      const auto edge = w.block_vertices(k.eblock);
      const Vec2 d = edge[(k.edge + 1) % edge.size()] - edge[k.edge];
      (std::abs(d.y()) < 1e-3 * d.norm() ? on_step : on_wall) = true;
    }
  }
  EXPECT_NEAR(on_base, weight, 1e-6 * weight);
  EXPECT_TRUE(on_step);
  EXPECT_TRUE(on_wall);
  EXPECT_LT((w.block_centroid(square) - start).norm(), 1e-5);
}

// A concave meshed block dropped onto a fixed base (dynamic, contacts
// opening and closing): the same state to the bit with 1 and 2 threads.
TEST(MeshedBlocks, ConcaveMeshedBlockIsDeterministicAcrossThreadCounts) {
  std::uint64_t hashes[2];
  for (const int threads : {1, 2}) {
    Controls c;
    c.gravity = {0, -9.81};
    c.g1 = 1e-3;
    c.threads = threads;
    World w(c);
    const int base_rock = w.add_rock_material(test::granite());
    RockMaterial meshed = test::granite();
    meshed.mesh_size = 0.2;
    test::add_fixed_base(w, test::rectangle(-1, -1, 3, 1), base_rock);
    std::vector<Vec2> lifted = notched_block();
    for (Vec2& v : lifted) v = 0.25 * v + Vec2(0.5, 0.001);
    w.add_block(lifted, w.add_rock_material(meshed));
    for (int i = 0; i < 40; ++i) w.step();
    EXPECT_GT(w.contacts().size(), 0u);
    hashes[threads - 1] = w.state_hash();
  }
  EXPECT_EQ(hashes[0], hashes[1]);
}

// Four square blocks meeting at a corner: first-order, each of the four
// joint edges carries two facing-edge contacts (8) and the diagonal blocks
// none. Meshed at half the block size, each joint edge is two edges of the
// meshes: 16 facing-edge contacts (the joint's length shared among them), no
// contact inside a mesh, and no corner contact where the four meet (an
// element's narrower wedge there must not add one).
TEST(MeshedBlocks, FourBlocksMeetingAtACornerContactAsFirstOrderBlocksDo) {
  for (const double mesh : {0.0, 0.1}) {
    Controls c;
    c.g1 = 1e-4;
    c.mesh_size = mesh;
    World w(c);
    const int r = w.add_rock_material(test::granite());
    for (const auto& [x, y] : {std::pair{0.0, 0.0}, {0.2, 0.0}, {0.0, 0.2}, {0.2, 0.2}})
      w.add_block(test::rectangle(x, y, 0.2, 0.2), r);
    w.step();
    const std::size_t expected = mesh > 0 ? 16 : 8;
    EXPECT_EQ(w.contacts().size(), expected) << "mesh " << mesh;
    double length = 0;
    for (const Contact& k : w.contacts()) {
      EXPECT_GT(k.length, 0) << "a corner contact " << k.vblock << ":" << k.vertex << " on " << k.eblock;
      length += k.length;
    }
    EXPECT_NEAR(length, 4 * 0.2, 1e-12);  // each contact stands for half its pair's overlap
  }
}

// σxx (tension +) of the element under each receiver, per step, of an
// unjointed bar (ν = 0: the 1-D wave equation, c = sqrt(E/ρ) = 5000 m/s)
// meshed at `size` (by default 20 m long and one row of cells high; or the
// `outline` given, its left end at x = 0), its left end loaded by a pressure
// of one sine period (compression first) of 1 MPa at `frequency`.
struct BarRun {
  std::vector<double> x;  // per receiver: the centroid of the element under it, at the start
  std::vector<double> time;
  std::vector<std::vector<double>> sigma;  // per receiver
};

BarRun meshed_bar(double size, double frequency, std::vector<double> receivers, double t_end, double dt,
                  int threads = 0, std::uint64_t* hash = nullptr, MeshMass mass = MeshMass::Consistent,
                  std::vector<Vec2> outline = {}) {
  Controls c;
  c.mesh_mass = mass;
  c.integrator = Integrator::Newmark;
  c.g1 = dt;
  c.g2 = 0.01;
  c.threads = threads;
  c.mesh_size = size;
  World w(c);
  const int rock = w.add_rock_material(RockMaterial{2000, 50e9, 0.0});
  if (outline.empty()) outline = test::rectangle(0, 0, 20, size);
  const BlockId first = w.add_block(outline, rock);
  std::vector<EdgeRef> left;
  for (std::size_t b = first; b < w.block_count(); ++b) {
    const auto v = w.block_vertices(static_cast<BlockId>(b));
    for (int k = 0; k < 3; ++k)
      if (std::abs(v[k].x()) < 1e-9 && std::abs(v[(k + 1) % 3].x()) < 1e-9)
        left.push_back({static_cast<BlockId>(b), k});
  }
  std::vector<std::pair<double, double>> pulse;
  const double period = 1 / frequency;
  for (int i = 0; i <= 200; ++i) {
    const double t = period * i / 200;
    pulse.emplace_back(t, 1e6 * std::sin(2 * M_PI * frequency * t));
  }
  pulse.emplace_back(period + 1e-9, 0);
  const int load = w.add_pressure_load(left);
  w.set_pressure_history(load, History(pulse));
  std::vector<int> probes;
  for (const double x : receivers) probes.push_back(w.add_tracked_point(first, {x, size / 3}));
  BarRun run;
  run.sigma.resize(receivers.size());
  for (const int p : probes) run.x.push_back(w.block_centroid(w.tracked_block(p)).x());
  while (w.time() < t_end - dt / 2) {
    const StepStats s = w.step();
    EXPECT_EQ(s.step_cuts, 0);
    run.time.push_back(w.time());
    for (std::size_t r = 0; r < probes.size(); ++r)
      run.sigma[r].push_back(w.block_stress(w.tracked_block(probes[r])).x());
  }
  if (hash) *hash = w.state_hash();
  return run;
}

// The exact 1-D stress at x: the load travelling at c = 5000 m/s.
double exact_sigma(double x, double t, double frequency) {
  const double s = t - x / 5000;
  return s > 0 && s < 1 / frequency ? -1e6 * std::sin(2 * M_PI * frequency * s) : 0.0;
}

struct PulseError {
  // Relative: peak amplitude, time of the peak (from the travel time), the
  // largest difference from the exact pulse and its root mean square (over
  // the record, against the exact pulse's).
  double peak, arrival, shape, rms;
};

// The first compressive peak of the record against the exact pulse at the
// receiver's element centroid.
PulseError pulse_error(const BarRun& run, std::size_t r, double frequency) {
  const auto& s = run.sigma[r];
  const double x = run.x[r];
  const auto low = std::min_element(s.begin(), s.end()) - s.begin();
  const double exact_peak_time = x / 5000 + 0.25 / frequency;
  double shape = 0, difference = 0, pulse = 0;
  for (std::size_t n = 0; n < s.size(); ++n) {
    const double exact = exact_sigma(x, run.time[n], frequency);
    shape = std::max(shape, std::abs(s[n] - exact));
    difference += (s[n] - exact) * (s[n] - exact);
    pulse += exact * exact;
  }
  return {(s[low] - (-1e6)) / 1e6, (run.time[low] - exact_peak_time) / exact_peak_time, shape / 1e6,
          std::sqrt(difference / pulse)};
}

// Reference: d'Alembert's solution of the 1-D wave equation, σ(x, t) =
// −p(t − x/c). At 16 elements per wavelength (λ = 5 m at 1000 Hz, elements
// 0.3125 m) the first compressive peak 2 wavelengths in (x = 10 m, the
// element centred there) has the exact amplitude within 2 % and arrives
// within 2 % of the exact time; tolerances of the issue (the paper's λ/16).
TEST(MeshedBlocks, UnjointedMeshedBarCarriesThe1DWave) {
  const double f = 1000, size = 5000 / f / 16;
  const double x = 10 + size / 2;  // the cell just right of x = 10 m
  const BarRun run = meshed_bar(size, f, {x}, x / 5000 + 1.2 / f, 0.1 * size / 5000);
  const PulseError e = pulse_error(run, 0, f);
  std::printf("16 elements per wavelength: peak %+.3f %%, arrival %+.3f %%, shape (max-norm) %.3f %%\n", 100 * e.peak,
              100 * e.arrival, 100 * e.shape);
  EXPECT_LT(std::abs(e.peak), 0.02);
  EXPECT_LT(std::abs(e.arrival), 0.02);
}

// The same wave under the other element masses (MeshMass; docs/meshed_blocks.md
// has the table). Reference: d'Alembert's σ(x, t) = −p(t − x/c), 2 wavelengths
// in. Mixed (the mean of the consistent and the lumped mass, whose leading
// dispersion errors cancel): at 16 elements per wavelength the first
// compressive peak and its arrival within 2 % (the tolerance, as for
// the consistent mass), and the RMS difference from the exact pulse under
// half the consistent mass's (measured 3.2 % against 11.1 %). Lumped: the
// arrival within 2 % at 16 elements per wavelength (its peak is not: −6.6 %,
// the lagging short waves of the sine's kinks ride on it), and the largest
// and the RMS difference fall with the mesh (8, 16, 32 per wavelength).
TEST(MeshedBlocks, UnjointedMeshedBarCarriesThe1DWaveUnderEachMass) {
  const double f = 1000;
  auto run = [&](int per_wavelength, MeshMass mass) {
    const double size = 5000 / f / per_wavelength, x = 10 + size / 2;
    return pulse_error(meshed_bar(size, f, {x}, x / 5000 + 1.2 / f, 0.1 * size / 5000, 0, nullptr, mass), 0, f);
  };
  const PulseError consistent = run(16, MeshMass::Consistent), mixed = run(16, MeshMass::Mixed);
  std::printf("mixed mass, 16 per wavelength: peak %+.3f %%, arrival %+.3f %%, RMS %.2f %% (consistent %.2f %%)\n",
              100 * mixed.peak, 100 * mixed.arrival, 100 * mixed.rms, 100 * consistent.rms);
  EXPECT_LT(std::abs(mixed.peak), 0.02);
  EXPECT_LT(std::abs(mixed.arrival), 0.02);
  EXPECT_LT(mixed.rms, 0.5 * consistent.rms);
  std::vector<PulseError> lumped;
  for (const int per_wavelength : {8, 16, 32}) {
    lumped.push_back(run(per_wavelength, MeshMass::Lumped));
    std::printf("lumped mass, %d per wavelength: peak %+.3f %%, arrival %+.3f %%, shape %.2f %%, RMS %.2f %%\n",
                per_wavelength, 100 * lumped.back().peak, 100 * lumped.back().arrival, 100 * lumped.back().shape,
                100 * lumped.back().rms);
  }
  EXPECT_LT(std::abs(lumped[1].arrival), 0.02);
  for (std::size_t i = 1; i < lumped.size(); ++i) {
    EXPECT_LT(lumped[i].shape, lumped[i - 1].shape);
    EXPECT_LT(lumped[i].rms, lumped[i - 1].rms);
  }
}

// Mesh convergence (docs/meshed_blocks.md has the table, with 64): 8, 16, 32
// elements per wavelength, the same receiver 2 wavelengths in, Δt at a tenth
// of the elements' transit time. The dispersion of linear elements shrinks
// as (kh)²: every error falls as the mesh is refined.
TEST(MeshedBlocks, MeshedBarConvergesWithTheMesh) {
  const double f = 1000;
  std::vector<PulseError> errors;
  for (const int per_wavelength : {8, 16, 32}) {
    const double size = 5000 / f / per_wavelength;
    const double x = 10 + size / 2;
    const BarRun run = meshed_bar(size, f, {x}, x / 5000 + 1.2 / f, 0.1 * size / 5000);
    errors.push_back(pulse_error(run, 0, f));
    std::printf("| %d | %.4g | %+.2f %% | %+.2f %% | %.1f %% | %.1f %% |\n", per_wavelength, size,
                100 * errors.back().peak, 100 * errors.back().arrival, 100 * errors.back().shape,
                100 * errors.back().rms);
  }
  for (std::size_t i = 1; i < errors.size(); ++i) {
    EXPECT_LT(std::abs(errors[i].peak), std::abs(errors[i - 1].peak) + 1e-3);
    EXPECT_LT(errors[i].shape, errors[i - 1].shape);
    EXPECT_LT(errors[i].rms, errors[i - 1].rms);
  }
}

// The same 1-D wave in a concave bar meshed by CGAL: 20 m long and 1 m high
// (ν = 0: the 2-D bar is the 1-D one at any height), its last metre 2 m
// high (a step the pulse reaches after the record ends). Reference:
// d'Alembert's solution, as above, at the element under (10.16, 0.1) m;
// tolerance of the issue, 2 % on the first compressive peak and its arrival
// at 16 elements per wavelength (edges up to 0.3125 m; the refinement makes
// most of them shorter).
TEST(MeshedBlocks, ConcaveMeshedBarCarriesThe1DWave) {
  const double f = 1000, size = 5000 / f / 16;
  const std::vector<Vec2> outline{{0, 0}, {20, 0}, {20, 2}, {19, 2}, {19, 1}, {0, 1}};
  const BarRun run = meshed_bar(size, f, {10 + size / 2}, (10 + size / 2) / 5000 + 1.2 / f, 0.1 * size / 5000, 0,
                                nullptr, MeshMass::Consistent, outline);
  const PulseError e = pulse_error(run, 0, f);
  std::printf(
      "concave bar, 16 elements per wavelength: receiver element at x = %.3f m, peak %+.3f %%, arrival "
      "%+.3f %%, shape (max-norm) %.3f %%, RMS %.3f %%\n",
      run.x[0], 100 * e.peak, 100 * e.arrival, 100 * e.shape, 100 * e.rms);
  EXPECT_LT(std::abs(e.peak), 0.02);
  EXPECT_LT(std::abs(e.arrival), 0.02);
}

// Same answer to the bit for any thread count.
TEST(MeshedBlocks, MeshedBarIsDeterministicAcrossThreadCounts) {
  std::uint64_t one = 0, three = 0;
  meshed_bar(0.5, 500, {5.25}, 3e-4, 1e-5, 1, &one);
  meshed_bar(0.5, 500, {5.25}, 3e-4, 1e-5, 3, &three);
  EXPECT_EQ(one, three);
}

// A jointed bar for the meshed solve's preconditioners: seven 1 × 0.5 m
// blocks, four meshed at 0.125 m (128 elements, 154 unknowns each: sparse
// factors) and three at 0.25 m (32 elements, 46 unknowns: dense factors),
// and an eighth first-order one, joints of k_n = 1e11 Pa/m without tension or cohesion, ν = 0.25;
// one sine period of 2 MPa (compression first, 1000 Hz) on the left end.
// The tensile half opens joints behind the pulse: contacts open and close.
struct JointedMeshedRun {
  std::vector<double> sigma;  // σxx of the element under (3.56, 0.2) m, per step
  std::vector<Vec2> centroids;
  double largest_motion = 0;  // of a block's centroid, from its start
  long cg_iterations = 0;
  int factorisations = 0;
  std::uint64_t hash = 0;
};

JointedMeshedRun jointed_meshed_bar(MeshPreconditioning preconditioning, int threads) {
  Controls c;
  c.integrator = Integrator::Newmark;
  c.g1 = 5e-6;
  c.g2 = 0.01;
  c.threads = threads;
  c.solver.mesh_preconditioner = preconditioning;
  c.mesh_size = 0;  // the last block stays first-order: a mix of both kinds
  // The consistent mass, where the factors halve the iterations; under the
  // wave model's lumped mass they save 43 % (885 against 1541).
  c.mesh_mass = MeshMass::Consistent;
  World w(c);
  RockMaterial meshed{2000, 50e9, 0.25};
  meshed.mesh_size = 0.125;
  const int rock = w.add_rock_material(meshed), plain = w.add_rock_material(RockMaterial{2000, 50e9, 0.25});
  meshed.mesh_size = 0.25;
  const int coarse = w.add_rock_material(meshed);
  const int joint = w.add_joint_material(JointMaterial{30, 0, 0, 1e11, 0});
  for (int i = 0; i < 8; ++i)
    w.add_block(test::rectangle(i, 0, 1, 0.5), i < 4 ? rock : i < 7 ? coarse : plain, {joint, joint, joint, joint});
  std::vector<EdgeRef> left;
  for (std::size_t b = 0; b < w.block_count(); ++b) {
    const auto v = w.block_vertices(static_cast<BlockId>(b));
    for (std::size_t k = 0; k < v.size(); ++k)
      if (std::abs(v[k].x()) < 1e-9 && std::abs(v[(k + 1) % v.size()].x()) < 1e-9)
        left.push_back({static_cast<BlockId>(b), static_cast<int>(k)});
  }
  std::vector<std::pair<double, double>> pulse;
  for (int i = 0; i <= 100; ++i) pulse.emplace_back(1e-3 * i / 100, 2e6 * std::sin(2 * M_PI * i / 100));
  pulse.emplace_back(1e-3 + 1e-9, 0);
  w.set_pressure_history(w.add_pressure_load(left), History(pulse));
  const int probe = w.add_tracked_point(0, {3.56, 0.2});
  std::vector<Vec2> start;
  for (std::size_t b = 0; b < w.block_count(); ++b) start.push_back(w.block_centroid(static_cast<BlockId>(b)));
  JointedMeshedRun run;
  for (int step = 0; step < 300; ++step) {
    const StepStats s = w.step();
    EXPECT_EQ(s.step_cuts, 0);
    run.cg_iterations += s.cg_iterations;
    run.factorisations += s.factorisations;
    run.sigma.push_back(w.block_stress(w.tracked_block(probe)).x());
  }
  for (std::size_t b = 0; b < w.block_count(); ++b) {
    run.centroids.push_back(w.block_centroid(static_cast<BlockId>(b)));
    run.largest_motion = std::max(run.largest_motion, (run.centroids.back() - start[b]).norm());
  }
  run.hash = w.state_hash();
  return run;
}

// The meshed blocks' factors (MeshPreconditioning::BlockFactor) and the
// nodes' 2×2 blocks (NodeJacobi) precondition the same system: both solves
// stop at cg_tolerance (1e-10 of the residual), so the two runs agree to
// far below the signal. Tolerances: the receiver's σxx within 1e-6 of the
// pulse's peak (2 MPa) at every step, every block's centroid within 1e-6 of
// the largest motion of a centroid. And the factors must pay: fewer than half
// the CG iterations.
TEST(MeshedBlocks, MeshFactorsSolveToTheSameAnswerInFewerIterations) {
  const JointedMeshedRun factor = jointed_meshed_bar(MeshPreconditioning::BlockFactor, 0);
  const JointedMeshedRun jacobi = jointed_meshed_bar(MeshPreconditioning::NodeJacobi, 0);
  double sigma_difference = 0, sigma_peak = 0, centroid_difference = 0;
  for (std::size_t n = 0; n < factor.sigma.size(); ++n) {
    sigma_difference = std::max(sigma_difference, std::abs(factor.sigma[n] - jacobi.sigma[n]));
    sigma_peak = std::max(sigma_peak, std::abs(jacobi.sigma[n]));
  }
  for (std::size_t b = 0; b < factor.centroids.size(); ++b)
    centroid_difference = std::max(centroid_difference, (factor.centroids[b] - jacobi.centroids[b]).norm());
  std::printf(
      "jointed meshed bar, 300 steps: CG iterations %ld (factors, %d factorisations) against %ld (node "
      "Jacobi); σxx peak %.4g Pa, largest difference %.3g Pa; centroids apart by at most %.3g m (moved up to "
      "%.3g m)\n",
      factor.cg_iterations, factor.factorisations, jacobi.cg_iterations, sigma_peak, sigma_difference,
      centroid_difference, jacobi.largest_motion);
  EXPECT_GT(sigma_peak, 0.5e6);
  EXPECT_LT(sigma_difference, 1e-6 * 2e6);
  EXPECT_LT(centroid_difference, 1e-6 * jacobi.largest_motion);
  EXPECT_LT(2 * factor.cg_iterations, jacobi.cg_iterations);
  EXPECT_GT(factor.factorisations, 0);
}

// The factors are made and applied per meshed block in parallel: the same
// state to the bit with 1 and 3 threads.
TEST(MeshedBlocks, MeshFactorsAreDeterministicAcrossThreadCounts) {
  EXPECT_EQ(jointed_meshed_bar(MeshPreconditioning::BlockFactor, 1).hash,
            jointed_meshed_bar(MeshPreconditioning::BlockFactor, 3).hash);
}

}  // namespace
