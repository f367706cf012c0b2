// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Block generation: cut a rock domain into blocks by joint sets, explicit
// joint lines and excavations (holes).
//
// Plain data in, plain data out; nothing here knows the World, Lua or OpenGL.
//
//   CutInput in;                      // domain, holes, sets, lines, regions
//   BlockSet blocks = cut_blocks(in); // throws dda::Error on bad input
//
// Conventions (see docs/formulation.md, "Block generation"):
//  - SI units (metres). Angles in degrees: a joint set's dip is measured from
//    the +x axis, counter-clockwise (0 = horizontal, 90 = vertical).
//  - A set's spacing is measured perpendicular to its joints, and one joint
//    of the set passes through its origin.
//  - Messages number user items from 1 ("hole 1", "joint set 2"), like the
//    vertex numbers of validate_simple_polygon; indices in the data are 0-based.
#include <cstdint>
#include <utility>
#include <vector>

#include "core/types.hpp"
#include "geometry/edge.hpp"

namespace dda::geometry {

// The cut's memory per joint crossing or input segment (about 0.6 to 0.85
// kB measured, docs/robustness.md): cut_blocks refuses before cutting what
// cannot fit, and the callers that make many segments (a circle's) before
// making them.
inline constexpr double kCutBytesPerCrossing = 1000;

// A family of parallel joints.
struct JointSet {
  double dip_deg = 0;          // direction of the joints, degrees from +x, counter-clockwise
  double spacing = 1;          // distance between neighbouring joints, perpendicular to them (m)
  Vec2 origin = Vec2::Zero();  // a point one joint of the set passes through
  int joint_material = 0;
  // Persistence: 0 = every joint crosses the whole domain. Otherwise each
  // joint line is a row of traces of this length separated by rock bridges
  // of bridge_length, starting at a random phase along each line (drawn from
  // the seed) so that neighbouring lines do not line their bridges up.
  double trace_length = 0;
  double bridge_length = 0;
  // Optional random variation (standard deviations; 0 = none). Spacing and
  // trace samples are truncated at 10 % of their mean so they stay positive.
  // For persistent sets the dip varies per joint line; for non-persistent
  // sets per trace (each trace turns about its own midpoint).
  double spacing_sd = 0;
  double dip_sd_deg = 0;
  double trace_sd = 0;
  // Seed of the set's random numbers (trace phase of non-persistent sets and
  // the variations above). The same seed gives the same joints with any
  // compiler and standard library: the generator (SplitMix64) and the normal
  // sampling are written out in geometry/random.hpp, not taken from <random>.
  std::uint64_t seed = 0;
};

// An explicit joint: a straight segment. Parts outside the domain or inside a
// hole are dropped; parts that close no block are removed with the other
// dangling joints.
struct JointLine {
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();
  int joint_material = 0;
};

// Blocks whose centroid lies in `polygon` get `rock_material`. When regions
// overlap, the last one listed wins (regions paint over each other in order).
struct MaterialRegion {
  std::vector<Vec2> polygon;
  int rock_material = 0;
};

// Blocks thinner on average than 8 snap tolerances are artefacts of nearly
// coincident joints and are always merged; the policy is for blocks that are
// real but smaller than min_block_area.
enum class SliverPolicy {
  Merge,  // merge each such block into the neighbour sharing the longest joint length with it
  Error,  // throw dda::Error listing them (count, area and place of the first five)
};

struct CutInput {
  std::vector<Vec2> domain;              // simple polygon, either orientation
  std::vector<std::vector<Vec2>> holes;  // simple polygons strictly inside the domain, disjoint
  std::vector<JointSet> sets;
  std::vector<JointLine> lines;
  std::vector<MaterialRegion> regions;
  int default_rock_material = 0;
  double min_block_area = 0;  // m²; blocks below it are merged or reported
  SliverPolicy sliver_policy = SliverPolicy::Merge;
  // Points closer than this are one vertex, and a point this close to a
  // segment lies on it. 0 = 1e-9 × the larger side of the domain's bounding box.
  double snap_tolerance = 0;
  // A hole no joint reaches, or a closed loop of joints touching no other
  // joint, would leave a block with a hole in it; a loop touching the others
  // at a single point would leave a block whose outline passes twice through
  // that point. DDA can represent neither.
  // -1 (default): report it as an error, naming the place.
  // A joint material id ≥ 0: cut such loops free automatically with straight
  // joints of this material, each running from the loop to the first joint or
  // boundary it meets: a free loop gets two horizontal cuts (from its
  // rightmost vertex to the right and from its leftmost vertex to the left),
  // a loop touching at one point gets one (from an extreme vertex that is not
  // the touching point, along x or y; failing that, square to its longest edge).
  int inner_cut_material = -1;
};

struct CutBlock {
  // Counter-clockwise; only true corners (where the outline goes straight on
  // and the edge tag does not change, the vertex is left out). A neighbour's
  // corner may lie inside one of this block's edges (a T-junction).
  std::vector<Vec2> vertices;
  std::vector<EdgeTag> edges;  // edge k runs from vertices[k] to vertices[k+1]
  int rock_material = 0;
  double area = 0;
  Vec2 centroid = Vec2::Zero();
};

// Figures from one cut, for benchmarks and diagnostics.
struct CutStats {
  int input_segments = 0;  // boundary edges + joint segments fed to the arrangement
  int arrangement_rounds = 0;
  int vertices = 0;  // of the arrangement inside the rock
  int edges = 0;     // of the arrangement inside the rock, before tree cutting
  int dangling_edges_removed = 0;
  int slivers_merged = 0;  // blocks below min_block_area (or degenerate) merged into a neighbour
  int inner_cuts = 0;      // automatic cuts added for inner loops (inner_cut_material)
};

enum class BoxSelect {
  Centroid,  // the block's centroid lies in the box
  Inside,    // every vertex of the block lies in the box
  Overlap,   // the block and the box share some area or boundary
};

struct BlockSet {
  std::vector<CutBlock> blocks;
  double snap_tolerance = 0;  // the tolerance the cut used (default for queries)
  double expected_area = 0;   // domain area minus hole areas
  int hole_count = 0;
  CutStats stats;

  // Blocks whose closed outline contains p (within tol; tol < 0 → snap
  // tolerance). Usually one; two or more on a shared edge or corner; none in
  // a hole or outside the domain. Ascending block order.
  std::vector<int> blocks_containing(const Vec2& p, double tol = -1) const;
  // Boxes are closed and widened by the snap tolerance.
  std::vector<int> blocks_in_box(const Vec2& lo, const Vec2& hi, BoxSelect mode = BoxSelect::Centroid) const;
  // Edges lying on the segment [a, b]: both end points within tol of it.
  std::vector<EdgeRef> edges_on_segment(const Vec2& a, const Vec2& b, double tol = -1) const;
  // Edges with both end points in the box.
  std::vector<EdgeRef> edges_in_box(const Vec2& lo, const Vec2& hi) const;
  std::vector<EdgeRef> domain_boundary_edges() const;
  std::vector<EdgeRef> hole_boundary_edges(int hole) const;  // 0-based hole index

  const EdgeTag& tag(EdgeRef e) const { return blocks[e.block].edges[e.edge]; }
  std::pair<Vec2, Vec2> edge_points(EdgeRef e) const;
  double edge_length(EdgeRef e) const;
  double total_area() const;
};

// Cuts the domain into blocks, in reading order (rows of centroids from the
// bottom, left to right). Deterministic: the same input gives the same blocks,
// bit for bit. The block areas sum to the domain area minus the holes to
// rounding; where snapping had to move vertices (joints nearly touching),
// by at most about the snap tolerance times the joint length involved.
// Throws dda::Error, naming the input item and
// the cause, for unusable input: a domain or hole that is not a simple
// polygon, a hole outside the domain or crossing its boundary or another hole,
// non-finite numbers, non-positive spacing, a joint set that would produce an
// unreasonable number of joints, negative material ids, slivers under
// SliverPolicy::Error, or an inner loop with inner_cut_material < 0.
BlockSet cut_blocks(const CutInput& input);

}  // namespace dda::geometry
