// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Meshed (deformable) blocks: a block given a mesh size is cut into
// constant-strain triangles (CST) whose corners are shared mesh nodes.
//
// A CST's displacement field is linear, exactly the first-order DDA field
// T(x, y)·D of a triangle: each element is stored as a block of its own
// (Blocks: its outline, centroid, moments, stress, time-scheme state), so
// contacts, loads, boundaries, output and monitors treat it as any block.
// What makes the elements one deformable block is that their six DDA
// unknowns are not free: D_e = A_e·u_e, u_e the displacements of the
// element's three nodes and A_e = [T(p1); T(p2); T(p3)]⁻¹ (the 6×6 matrix
// that puts T through the three corners). Neighbouring elements share the
// nodes, so the displacement is continuous inside the block: no springs and
// no joints between the elements. The step solves for the nodes
// (assembly/mesh_reduction.hpp) and hands each element its D_e; the rest of
// the step reads D_e as it reads a first-order block's D.
//
// Contacts stay on the block's outline: elements of one mesh never contact
// each other, an edge inside a mesh carries no contact, and a vertex makes
// contacts only from an element with an outline edge at it (mesh_contacts.cpp).
//
// The mesher (mesh_polygon) takes convex blocks to the structured mesher
// (mesh_convex_polygon): a triangle is divided into m² similar triangles, a
// quadrilateral into a bilinear grid of cells of four triangles about their
// centres, a convex polygon of five or more corners into a fan from its
// centroid whose triangles are divided alike. Concave blocks go to CGAL's
// constrained Delaunay mesher (mesh_concave_polygon, block/mesh_cgal.cpp, the
// one file that includes CGAL; docs/meshed_blocks.md says why).
#include <array>
#include <span>
#include <string>
#include <vector>

#include "block/blocks.hpp"
#include "core/types.hpp"

namespace dda {

struct TriangleMesh {
  std::vector<Vec2> nodes;
  std::vector<std::array<int, 3>> triangles;  // node ids, counter-clockwise
  // Per triangle edge k (its node k → k + 1): the outline edge it lies on,
  // or -1 for an edge inside the polygon.
  std::vector<std::array<int, 3>> outline_edge;
};

// Meshes a simple polygon (counter-clockwise) with triangles of edges no
// longer than about `size`: convex outlines with mesh_convex_polygon, others
// with mesh_concave_polygon. Throws dda::Error naming `what` when the size is
// not positive or the mesh would be too large.
TriangleMesh mesh_polygon(std::span<const Vec2> outline, double size, const std::string& what);

// The structured mesher for a convex polygon. Throws dda::Error naming `what`
// when the polygon is not convex.
TriangleMesh mesh_convex_polygon(std::span<const Vec2> outline, double size, const std::string& what);

// CGAL's constrained Delaunay mesher (Ruppert's refinement, exact
// predicates) for a simple polygon of any shape: every outline vertex is a
// node, every outline edge is first cut into equal segments no longer than
// `size`, and the refinement leaves no triangle edge longer than `size` and
// no angle under kConcaveMeshMinimumAngle (except at outline corners sharper
// than that). The result depends on the outline only: the same triangles,
// numbered the same, on every run. Throws dda::Error naming `what` when the
// outline cannot be meshed (its edges cross) or the mesh would be too large.
TriangleMesh mesh_concave_polygon(std::span<const Vec2> outline, double size, const std::string& what);

// The refinement's bound on the squared sine of an element's smallest angle
// (CGAL's default, the largest for which Ruppert's refinement is proven to
// end): asin(sqrt(0.125)) = 20.7°.
inline constexpr double kConcaveMeshShapeBound = 0.125;

// A block is refused before it is meshed (or, for CGAL, while it is refined)
// when its mesh would hold more elements than this: bad input must not
// exhaust memory before the first step's memory check.
inline constexpr double kMaxMeshElements = 4e6;

// The elements mesh_polygon makes of `outline` at `size`: the structured
// mesher's count exactly, area / (0.2·size²) for the concave mesher (its
// refinement's triangles average about 0.2·size²: 31 953 measured on an L
// of 64 m² at 0.1 m, against 32 000).
double estimated_mesh_elements(std::span<const Vec2> outline, double size);
// The memory an element takes by the model's first step: the first step's
// estimate for a triangle (2.5 kB a block, 0.5 kB a vertex; measured 2.8 kB
// on 40 000 and 160 000 structured elements, 3.1 kB on 32 000 of CGAL's,
// docs/robustness.md). A block is refused, with the estimate, before a mesh
// that cannot fit is made.
inline constexpr double kMeshBytesPerElement = 4000;

// Sets mesh.outline_edge from the geometry: a triangle edge lies on the
// outline edge that holds both its ends (within `tol`).
void label_outline_edges(TriangleMesh& mesh, std::span<const Vec2> outline, double tol);

// The element of block b's mesh whose outline holds p (b itself when it is
// not meshed, or when no element holds p: then the nearest element of its
// mesh). Points of loads, fixed points and monitors are put on it.
BlockId element_under(const Blocks& blocks, BlockId b, const Vec2& p);

// The centroid of meshed block `mesh` (its elements' area-weighted centroids).
Vec2 mesh_centroid(const Blocks& blocks, int mesh);

// The number of mesh nodes (0 when no block is meshed).
int mesh_node_count(const Blocks& blocks);

}  // namespace dda
