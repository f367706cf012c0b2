// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The mesher for concave blocks: CGAL's constrained Delaunay triangulation
// refined by Ruppert's algorithm (Delaunay_mesher_2). The one file of the
// engine that includes CGAL (engine/CMakeLists.txt compiles it apart, with
// CGAL's -frounding-math, so the rest of the engine is built as before and
// the header-heavy include costs one translation unit).
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "block/mesh.hpp"
#include "core/error.hpp"
#include "geometry/polygon.hpp"

namespace dda {

namespace {

// Exact predicates (orientation, in-circle) decide the triangulation, so
// round-off cannot make it inconsistent; the Steiner points themselves are
// computed in double. Constraints that cross are an error, not a new vertex.
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Tds = CGAL::Triangulation_data_structure_2<CGAL::Delaunay_mesh_vertex_base_2<Kernel>,
                                                 CGAL::Delaunay_mesh_face_base_2<Kernel>>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::No_constraint_intersection_tag>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;
using Mesher = CGAL::Delaunay_mesher_2<Cdt, Criteria>;
using VertexHandle = Cdt::Vertex_handle;

Error too_many_elements(const std::string& what, double size) {
  return Error(msg(what, ": mesh size ", size, " m would cut this block into more than ", kMaxMeshElements,
                   " elements; use a larger mesh size"));
}

// The refined triangulation as a TriangleMesh whose numbering depends on the
// geometry only, not on CGAL's storage order: the outline's own points first
// (in the order inserted), then the points the refinement added, sorted by
// (x, y); triangles counter-clockwise from their lowest node, sorted.
TriangleMesh canonical_mesh(const Cdt& cdt, const std::vector<VertexHandle>& boundary) {
  std::map<VertexHandle, int> id;
  TriangleMesh mesh;
  for (const VertexHandle v : boundary) {
    id.emplace(v, static_cast<int>(mesh.nodes.size()));
    mesh.nodes.emplace_back(v->point().x(), v->point().y());
  }
  std::vector<std::pair<Vec2, VertexHandle>> added;
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v)
    if (!id.count(v)) added.emplace_back(Vec2(v->point().x(), v->point().y()), v);
  std::sort(added.begin(), added.end(), [](const auto& a, const auto& b) {
    return std::tie(a.first.x(), a.first.y()) < std::tie(b.first.x(), b.first.y());
  });
  for (const auto& [p, v] : added) {
    id.emplace(v, static_cast<int>(mesh.nodes.size()));
    mesh.nodes.push_back(p);
  }
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    std::array<int, 3> t{id.at(f->vertex(0)), id.at(f->vertex(1)), id.at(f->vertex(2))};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    mesh.triangles.push_back(t);
  }
  std::sort(mesh.triangles.begin(), mesh.triangles.end());
  return mesh;
}

}  // namespace

TriangleMesh mesh_concave_polygon(std::span<const Vec2> v, double size, const std::string& what) {
  if (!(size > 0) || !std::isfinite(size)) throw Error(msg(what, ": mesh size ", size, " must be positive"));
  const int n = static_cast<int>(v.size());
  // Refinement makes triangles of edges up to `size` (area about 0.43·size²)
  // and smaller near short outline edges; ten per size² bounds the count
  // from above for outlines without features much smaller than `size` (the
  // refinement loop below catches the others).
  if (10 * polygon_moments(v).area / (size * size) > kMaxMeshElements) throw too_many_elements(what, size);
  double longest = 0;
  for (int k = 0; k < n; ++k) longest = std::max(longest, (v[(k + 1) % n] - v[k]).norm());
  Cdt cdt;
  std::vector<VertexHandle> boundary;
  try {
    // Each outline edge cut into equal segments no longer than `size`, as the
    // structured mesher cuts it: nodes on every outline vertex and along every
    // edge, so contacts on the outline meet nodes at the mesh's spacing.
    for (int k = 0; k < n; ++k) {
      const Vec2 a = v[k], d = v[(k + 1) % n] - v[k];
      const int m = std::max(1, static_cast<int>(std::ceil(d.norm() / size - 1e-9)));
      for (int i = 0; i < m; ++i) {
        const Vec2 p = a + d * (double(i) / m);
        boundary.push_back(cdt.insert(Kernel::Point_2(p.x(), p.y())));
      }
    }
    for (std::size_t i = 0; i < boundary.size(); ++i)
      cdt.insert_constraint(boundary[i], boundary[(i + 1) % boundary.size()]);
    Mesher mesher(cdt, Criteria(kConcaveMeshShapeBound, size));
    mesher.init();  // no seeds: the domain is the inside of the outline
    while (!mesher.is_refinement_done()) {
      mesher.step_by_step_refine_mesh();
      if (static_cast<double>(cdt.number_of_faces()) > kMaxMeshElements) throw too_many_elements(what, size);
    }
  } catch (const Cdt::Intersection_of_constraints_exception&) {
    throw Error(msg(what, ": its outline crosses or touches itself, so it cannot be meshed; give a simple polygon"));
  } catch (const CGAL::Failure_exception& e) {
    throw Error(msg(what, ": CGAL's mesher failed on this outline (", e.what(),
                    "); give this block's material no mesh size, or cut the block with a joint line"));
  }
  TriangleMesh mesh = canonical_mesh(cdt, boundary);
  label_outline_edges(mesh, v, 1e-9 * longest);
  return mesh;
}

}  // namespace dda
