// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "contact/narrow_phase.hpp"

#include <algorithm>
#include <cmath>

#include "core/parallel.hpp"
#include "geometry/polygon.hpp"

namespace dda {

namespace {

// Geometry of one edge of a block: from vertex k to k+1 (counter-clockwise,
// so the block lies to the left and the outward normal points right).
struct Edge {
  Vec2 p0, p1, t, n;  // ends, unit direction, outward unit normal
  double length;
};

// Edge k of every block and the convexity of vertex k, computed once per
// detection and shared by all pairs (indexed like blocks.vertices).
struct EdgeTable {
  std::vector<Edge> edge;
  std::vector<char> convex;
};

Edge make_edge(const BlockPolygons& blocks, int b, int k) {
  Edge e;
  e.p0 = blocks.vertex(b, k);
  e.p1 = blocks.vertex(b, k + 1);
  const Vec2 d = e.p1 - e.p0;
  e.length = d.norm();
  e.t = d / e.length;
  e.n = Vec2(e.t.y(), -e.t.x());
  return e;
}

EdgeTable make_edge_table(const BlockPolygons& blocks) {
  EdgeTable table;
  table.edge.resize(blocks.vertices.size());
  table.convex.resize(blocks.vertices.size());
  parallel_for_each(
      blocks.count(),
      [&](std::size_t bi) {
        const int b = static_cast<int>(bi);
        for (int k = 0; k < blocks.size(b); ++k) {
          table.edge[blocks.start[b] + k] = make_edge(blocks, b, k);
          const Vec2& v = blocks.vertex(b, k);
          table.convex[blocks.start[b] + k] = cross(v - blocks.vertex(b, k - 1), blocks.vertex(b, k + 1) - v) > 0;
        }
      },
      64);
  return table;
}

bool facing(const Edge& e, const Edge& f, double parallel_sin) {
  // Anti-parallel within the tolerance: e.t·f.t ≈ -1.
  return e.t.dot(f.t) < 0 && std::abs(cross(e.t, f.t)) <= parallel_sin;
}

// How edge ea of one block lies along a facing edge eb of another: where
// ea's ends fall along eb (s0 for ea's start, s1 for its end: ea runs the
// other way), the shared length lo..hi along eb (hi < lo: a gap between their
// ends), and ea's gap outside eb at lo and at hi.
struct FacingSpan {
  double s0, s1, lo, hi, glo, ghi;
  double overlap() const { return hi - lo; }
};

FacingSpan facing_span(const Edge& ea, const Edge& eb) {
  FacingSpan f;
  f.s0 = (ea.p0 - eb.p0).dot(eb.t), f.s1 = (ea.p1 - eb.p0).dot(eb.t);
  f.lo = std::max(0.0, f.s1), f.hi = std::min(eb.length, f.s0);
  const double g0 = (ea.p0 - eb.p0).dot(eb.n), g1 = (ea.p1 - eb.p0).dot(eb.n);
  auto gap_at = [&](double pos) { return f.s0 == f.s1 ? g0 : g1 + (pos - f.s1) / (f.s0 - f.s1) * (g0 - g1); };
  f.glo = gap_at(f.lo), f.ghi = gap_at(f.hi);
  return f;
}

// How clearly a vertex wedge lies outside an edge: the smaller of its two
// directions' components along the edge's outward normal.
double entrance_score(const std::pair<Vec2, Vec2>& wedge, const Edge& f) {
  return std::min(wedge.first.dot(f.n), wedge.second.dot(f.n));
}

constexpr double kWedgeSlack = 1e-3;

struct PairDetector {
  const BlockPolygons& blocks;
  const EdgeTable& table;
  std::span<const int> edge_joint;
  const NarrowPhaseSettings& s;
  std::vector<Contact>& out;
  std::vector<AlignedEdges>* aligned;        // where the pair's aligned edges go (none: not wanted)
  std::vector<std::pair<int, int>> covered;  // (block, vertex) already in a facing-edge contact

  // Adds the contact unless its vertex has gone round the edge's corner;
  // returns whether it did.
  bool add(int vb, int vertex, int eb, int edge, double length, double scale = 1) {
    Contact c;
    c.vblock = vb;
    c.vertex = vertex;
    c.eblock = eb;
    c.edge = edge;
    c.joint = edge_joint[blocks.start[eb] + edge];
    c.length = length;
    c.scale = scale;
    if (passed_corner(blocks, c)) return false;
    out.push_back(c);
    return true;
  }
  bool is_covered(int b, int k) const {
    return std::find(covered.begin(), covered.end(), std::pair<int, int>(b, k)) != covered.end();
  }
  int wrap(int b, int k) const { return ((k % blocks.size(b)) + blocks.size(b)) % blocks.size(b); }
  const Edge& edge_of(int b, int k) const { return table.edge[blocks.start[b] + wrap(b, k)]; }
  bool is_convex(int b, int k) const { return table.convex[blocks.start[b] + wrap(b, k)]; }
  // Unit directions from vertex k along its two edges.
  std::pair<Vec2, Vec2> wedge_of(int b, int k) const { return {-edge_of(b, k - 1).t, edge_of(b, k).t}; }

  void facing_edges(int a, int b) {
    for (int ia = 0; ia < blocks.size(a); ++ia) {
      const Edge& ea = edge_of(a, ia);
      for (int ib = 0; ib < blocks.size(b); ++ib) {
        const Edge& eb = edge_of(b, ib);
        if (!facing(ea, eb, s.parallel_sin)) continue;
        const FacingSpan span = facing_span(ea, eb);
        const double s0 = span.s0, s1 = span.s1, lo = span.lo, hi = span.hi, glo = span.glo, ghi = span.ghi;
        const double shorter = std::min(ea.length, eb.length);
        const double max_depth = std::min(s.range, 0.25 * shorter);
        const double tie = kEndTie * shorter;
        if (aligned && std::abs(hi - lo) < tie && std::min(glo, ghi) <= kCornerMargin * shorter &&
            std::min(glo, ghi) >= -max_depth)
          aligned->push_back({a, ia, b, ib, hi - lo});
        if (hi - lo <= 1e-6 * shorter) continue;  // no shared length (an aligned corner at most)
        if (std::min(glo, ghi) > s.range || std::min(glo, ghi) < -max_depth) continue;
        const double share = 0.5 * (hi - lo);
        const double scale = std::min(1.0, (hi - lo) / tie);
        const int a_lo = wrap(a, ia + 1), a_hi = ia;  // a's vertices at the low / high end
        const int b_lo = ib, b_hi = wrap(b, ib + 1);  // b's vertices at the low / high end
        // Low end of the overlap (near eb's start).
        // (A vertex that has gone round a corner makes no contact here and
        // stays free for the vertex-vertex and vertex-edge search.)
        if (s1 >= -tie) {
          if (add(a, a_lo, b, ib, share, scale)) {
            covered.emplace_back(a, a_lo);
            if (s1 <= tie) covered.emplace_back(b, b_lo);
          }
        } else if (add(b, b_lo, a, ia, share, scale)) {
          covered.emplace_back(b, b_lo);
        }
        // High end (near eb's end).
        if (s0 <= eb.length + tie) {
          if (add(a, a_hi, b, ib, share, scale)) {
            covered.emplace_back(a, a_hi);
            if (s0 >= eb.length - tie) covered.emplace_back(b, b_hi);
          }
        } else if (add(b, b_hi, a, ia, share, scale)) {
          covered.emplace_back(b, b_hi);
        }
      }
    }
  }

  // Does an edge at vertex k of block x face an edge at vertex l of block y?
  bool aligned_corner(int x, int k, int y, int l) const {
    for (int ex : {k - 1, k})
      for (int ey : {l - 1, l})
        if (facing(edge_of(x, wrap(x, ex)), edge_of(y, wrap(y, ey)), s.parallel_sin)) return true;
    return false;
  }

  // Convex vertices of x near the interior of edges of y.
  void vertex_to_edge(int x, int y) {
    for (int k = 0; k < blocks.size(x); ++k) {
      if (is_covered(x, k) || !is_convex(x, k)) continue;
      const Vec2& v = blocks.vertex(x, k);
      const auto wedge = wedge_of(x, k);
      const Edge &prev = edge_of(x, k - 1), &next = edge_of(x, k);
      for (int f = 0; f < blocks.size(y); ++f) {
        const Edge& e = edge_of(y, f);
        const double along = (v - e.p0).dot(e.t);
        if (along <= 0 || along >= e.length) continue;
        const double gap = (v - e.p0).dot(e.n);
        if (gap > s.range || gap < -std::min(s.range, 0.25 * e.length)) continue;
        // Near a convex end: a vertex-vertex approach (the entrance rule picks
        // one edge). Near a reflex end the vertex is in a notch of y and may
        // meet both edges there: each is a vertex-edge contact.
        if (((v - e.p0).squaredNorm() <= s.range * s.range && is_convex(y, f)) ||
            ((v - e.p1).squaredNorm() <= s.range * s.range && is_convex(y, f + 1)))
          continue;
        if (facing(prev, e, s.parallel_sin) || facing(next, e, s.parallel_sin)) continue;
        if (entrance_score(wedge, e) < -kWedgeSlack) continue;
        add(x, k, y, f, 0.0);
      }
    }
  }

  // Vertex-vertex approaches: one contact per vertex pair (entrance rule).
  void vertex_to_vertex(int a, int b) {
    for (int k = 0; k < blocks.size(a); ++k) {
      if (is_covered(a, k)) continue;
      const Vec2& va = blocks.vertex(a, k);
      for (int l = 0; l < blocks.size(b); ++l) {
        if (is_covered(b, l)) continue;
        const Vec2& vb = blocks.vertex(b, l);
        if ((va - vb).squaredNorm() > s.range * s.range) continue;
        if (aligned_corner(a, k, b, l)) continue;
        struct Option {
          int vblock, vertex, eblock, edge;
          double score;
        };
        Option best{-1, -1, -1, -1, -kWedgeSlack};
        // Edge ey of y ends at y's vertex vy; other_ey is y's other edge there.
        auto consider = [&](int x, int vx, int y, int ey, int other_ey, int corner) {
          if (!is_convex(x, vx)) return;
          const Edge& e = edge_of(y, ey);
          const double gap = (blocks.vertex(x, vx) - e.p0).dot(e.n);
          if (gap < -std::min(s.range, 0.25 * e.length)) return;
          // Behind the line of ey but clearly outside y past its other edge:
          // the vertex is beside y's corner, not in it, and the negative gap
          // is a false penetration (a search range wider than the blocks
          // pairs vertices up to a metre apart across a chamber corner).
          // Only at a convex corner: beside a reflex one, outside the other
          // edge's line is still inside y (a vertex on a bench's floor, a
          // few centimetres from the foot of the wall above it).
          const Edge& other = edge_of(y, other_ey);
          const double other_gap = (blocks.vertex(x, vx) - other.p0).dot(other.n);
          if (is_convex(y, corner) && gap < 0 && other_gap > -gap && other_gap > 1e-6 * other.length) return;
          const double score = entrance_score(wedge_of(x, vx), e);
          if (score <= best.score) return;
          Contact option;
          option.vblock = x, option.vertex = vx, option.eblock = y, option.edge = ey;
          if (!passed_corner(blocks, option)) best = {x, vx, y, ey, score};
        };
        consider(a, k, b, wrap(b, l - 1), l, l);
        consider(a, k, b, l, wrap(b, l - 1), l);
        consider(b, l, a, wrap(a, k - 1), k, k);
        consider(b, l, a, k, wrap(a, k - 1), k);
        if (best.vblock >= 0) add(best.vblock, best.vertex, best.eblock, best.edge, 0.0);
      }
    }
  }
};

}  // namespace

bool passed_corner(const BlockPolygons& blocks, const Contact& c) {
  const int b = c.eblock, f = c.edge;
  const Vec2& v = blocks.vertex(c.vblock, c.vertex);
  const Vec2 &p0 = blocks.vertex(b, f), &p1 = blocks.vertex(b, f + 1);
  const Vec2 d = p1 - p0;
  const double length = d.norm();
  const Vec2 t = d / length, n(t.y(), -t.x());  // outward normal: the block lies left of the edge
  const double depth = -(v - p0).dot(n);        // behind the edge's line
  const double margin = kCornerMargin * length;
  if (depth <= margin) return false;
  // The corner at the nearer end, and the other edge there (from `before` to
  // `after`, counter-clockwise).
  const bool at_start = (v - p0).dot(t) < 0.5 * length;
  const Vec2& corner = at_start ? p0 : p1;
  const Vec2& before = at_start ? blocks.vertex(b, f - 1) : p0;
  const Vec2& after = at_start ? p1 : blocks.vertex(b, f + 2);
  if (cross(corner - before, after - corner) <= 0) return false;  // a reflex corner: the vertex can be inside
  // An element's corner whose other edge lies inside its mesh is no corner
  // of the block's outline: the outline goes on through the next element,
  // whose own edges judge a vertex there. Judged as a corner, a node of the
  // other block a fraction of a millimetre past the facing node (elements of
  // 0.125 m: a margin of 0.125 mm, under a joint's closure in a blast) lost
  // every contact of a compressed joint.
  if (blocks.is_inner_edge(b, at_start ? f - 1 : f + 1)) return false;
  const Vec2 other = at_start ? corner - before : after - corner;
  const Vec2 other_n = Vec2(other.y(), -other.x()) / other.norm();
  const double other_depth = -(v - corner).dot(other_n);  // behind the other edge's line (negative: outside)
  return depth > std::max(0.0, kCornerRatio * other_depth) + margin;
}

bool aligned_edges_slid(const BlockPolygons& blocks, const AlignedEdges& e) {
  if (e.a >= blocks.count() || e.b >= blocks.count() || e.edge_a >= blocks.size(e.a) || e.edge_b >= blocks.size(e.b))
    return true;
  const Edge ea = make_edge(blocks, e.a, e.edge_a), eb = make_edge(blocks, e.b, e.edge_b);
  const double tie = kEndTie * std::min(ea.length, eb.length);
  return facing_span(ea, eb).overlap() > std::max(0.0, e.overlap) + kAlignedSlide * tie;
}

bool slid_past_end(const BlockPolygons& blocks, const Contact& c) {
  const int b = c.eblock, f = c.edge;
  const Vec2& v = blocks.vertex(c.vblock, c.vertex);
  const Vec2 &p0 = blocks.vertex(b, f), &p1 = blocks.vertex(b, f + 1);
  const Vec2 &before = blocks.vertex(c.vblock, c.vertex - 1), &after = blocks.vertex(c.vblock, c.vertex + 1);
  const double length = (p1 - p0).norm();
  const double along = (v - p0).dot(p1 - p0) / length;
  if (along >= 0 && along <= length) return false;
  // Past a reflex corner the vertex runs into the next edge at once: any
  // distance beyond the corner margin. Past a convex one, the facing edges' tie.
  const bool at_start = along < 0;
  const Vec2& corner = at_start ? p0 : p1;
  const Vec2& prev = at_start ? blocks.vertex(b, f - 1) : p0;
  const Vec2& next = at_start ? p1 : blocks.vertex(b, f + 2);
  const bool reflex = cross(corner - prev, next - corner) < 0;
  const double own = std::max((v - before).norm(), (after - v).norm());
  const double tie = reflex ? kCornerMargin * length : kEndTie * std::min(length, own);
  return along < -tie || along > length + tie;
}

// The slacks: each test compares a distance (along or off an edge) with a
// threshold. Let every vertex of the two blocks move by at most δ. The
// vertex-to-edge vector r = v - p0 then changes by at most 2δ, the edge
// (length l) by 2δ, and its unit direction t and normal n by at most 4δ/l
// (|u/|u| - w/|w|| <= 2|u - w|/|u|), so r·t and r·n change by at most
// δ·(2 + 4|r|/l): a rate of change per unit δ. A test's room to its
// threshold divided by the sum of such rates bounds δ. Halved, less an
// allowance for rounding (far above the tests' own rounding errors), and at
// most an eighth of the edge (which then cannot shrink to nothing), it is
// the slack.
namespace {
double safe_slack(double room, double rate, double size, double coordinates) {
  const double slack = std::min(0.5 * room / rate, size / 8) - 1e-9 * (coordinates + size);
  return slack > 0 ? slack : 0;  // also when room is NaN (a degenerate edge)
}
double magnitude(const Vec2& p) { return p.cwiseAbs().maxCoeff(); }
}  // namespace

double transfer_slack(const BlockPolygons& blocks, const Contact& c) {
  const int b = c.eblock, f = c.edge;
  const Vec2& v = blocks.vertex(c.vblock, c.vertex);
  const Vec2 &p0 = blocks.vertex(b, f), &p1 = blocks.vertex(b, f + 1);
  const Vec2 &before = blocks.vertex(c.vblock, c.vertex - 1), &after = blocks.vertex(c.vblock, c.vertex + 1);
  const Vec2 d = p1 - p0, r = v - p0;
  const double length = d.norm();
  const Vec2 t = d / length, n(t.y(), -t.x());
  const double along = r.dot(t), depth = -r.dot(n);
  const double drift = 2 + 4 * r.norm() / length;  // rate of along and of depth
  // passed_corner is false while depth <= kCornerMargin·length.
  const double corner_room = kCornerMargin * length - depth;
  const double corner_rate = drift + 2 * kCornerMargin;
  // slid_past_end is false while -tie <= along <= length + tie, the tie of
  // either end being at least the smaller of the reflex and the convex one
  // (which moves at most 2·kEndTie·δ; the length at most 2δ).
  const double own = std::max((v - before).norm(), (after - v).norm());
  const double tie = std::min(kCornerMargin * length, kEndTie * std::min(length, own));
  const double end_room = std::min(along + tie, length + tie - along);
  const double end_rate = drift + 2 + 2 * kEndTie;
  const double coordinates =
      std::max({magnitude(v), magnitude(p0), magnitude(p1), magnitude(before), magnitude(after)});
  return std::min(safe_slack(corner_room, corner_rate, length, coordinates),
                  safe_slack(end_room, end_rate, length, coordinates));
}

double aligned_slack(const BlockPolygons& blocks, const AlignedEdges& e) {
  if (e.a >= blocks.count() || e.b >= blocks.count() || e.edge_a >= blocks.size(e.a) || e.edge_b >= blocks.size(e.b))
    return 0;
  const Edge ea = make_edge(blocks, e.a, e.edge_a), eb = make_edge(blocks, e.b, e.edge_b);
  const double shorter = std::min(ea.length, eb.length);
  const double room = std::max(0.0, e.overlap) + kAlignedSlide * kEndTie * shorter - facing_span(ea, eb).overlap();
  // The overlap min(l_b, s0) - max(0, s1): s0 and s1 are r·t of ea's ends
  // along eb (each rate at least l_b's, 2); the tie moves at most
  // 2·kEndTie·δ.
  const double rate =
      4 + 4 * ((ea.p0 - eb.p0).norm() + (ea.p1 - eb.p0).norm()) / eb.length + 2 * kAlignedSlide * kEndTie;
  const double coordinates = std::max({magnitude(ea.p0), magnitude(ea.p1), magnitude(eb.p0), magnitude(eb.p1)});
  return safe_slack(room, rate, shorter, coordinates);
}

namespace {
void detect_with_table(const BlockPolygons& blocks, const EdgeTable& table, std::span<const int> edge_joint, int a,
                       int b, const NarrowPhaseSettings& settings, std::vector<Contact>& out,
                       std::vector<AlignedEdges>* aligned) {
  PairDetector d{blocks, table, edge_joint, settings, out, aligned, {}};
  const std::size_t first = out.size();
  d.facing_edges(a, b);
  d.vertex_to_edge(a, b);
  d.vertex_to_edge(b, a);
  d.vertex_to_vertex(a, b);
  // One contact per identity (a vertex can bound two overlaps of the same edge
  // only in degenerate outlines; merge their lengths).
  std::sort(out.begin() + first, out.end(), identity_less);
  std::size_t w = first;
  for (std::size_t r = first; r < out.size(); ++r) {
    if (w > first && same_identity(out[w - 1], out[r]))
      out[w - 1].length += out[r].length;
    else
      out[w++] = out[r];
  }
  out.resize(w);
}
}  // namespace

void detect_pair_contacts(const BlockPolygons& blocks, std::span<const int> edge_joint, int a, int b,
                          const NarrowPhaseSettings& settings, std::vector<Contact>& out) {
  detect_with_table(blocks, make_edge_table(blocks), edge_joint, a, b, settings, out, nullptr);
}

std::vector<Contact> detect_contacts(const BlockPolygons& blocks, std::span<const int> edge_joint,
                                     std::span<const std::pair<int, int>> pairs, const NarrowPhaseSettings& settings,
                                     std::vector<AlignedEdges>* aligned) {
  const EdgeTable table = make_edge_table(blocks);
  const std::size_t chunks = chunk_count(pairs.size());
  std::vector<std::vector<Contact>> found(chunks);
  std::vector<std::vector<AlignedEdges>> found_aligned(chunks);
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    const std::size_t end = std::min(pairs.size(), (c + 1) * kChunk);
    for (std::size_t p = c * kChunk; p < end; ++p)
      detect_with_table(blocks, table, edge_joint, pairs[p].first, pairs[p].second, settings, found[c],
                        aligned ? &found_aligned[c] : nullptr);
  });
  if (aligned) {
    aligned->clear();
    for (const auto& f : found_aligned) aligned->insert(aligned->end(), f.begin(), f.end());
  }
  std::size_t total = 0;
  for (const auto& f : found) total += f.size();
  std::vector<Contact> contacts;
  contacts.reserve(total);
  for (const auto& f : found) contacts.insert(contacts.end(), f.begin(), f.end());
  return contacts;
}

}  // namespace dda
