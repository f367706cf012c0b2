// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "geometry/cutting.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "core/error.hpp"
#include "core/memory.hpp"
#include "geometry/arrangement.hpp"
#include "geometry/joint_sets.hpp"
#include "geometry/polygon.hpp"

namespace dda::geometry {
namespace {

// ---- Input checks -------------------------------------------------------------

// Ranks for the arrangement: boundary geometry is never moved by snapping.
constexpr int kJointRank = 0;
constexpr int kBoundaryRank = 2;
constexpr int kCornerRank = 3;

// A user-chosen snap tolerance above this share of the domain size would
// swallow real geometry.
constexpr double kMaxRelativeSnap = 1e-3;
constexpr int kMaxInnerCutPasses = 4;
constexpr double kMaxSetCrossings = 5e6;
constexpr double kFarLine = 1e6;  // domain sizes: joint lines reaching farther are clipped first
constexpr int kMaxCleanupPasses = 64;

bool finite(const Vec2& p) { return std::isfinite(p.x()) && std::isfinite(p.y()); }

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

double segment_distance(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  if (segments_cross_properly(a, b, c, d)) return 0;
  return std::min({distance_to_segment(a, c, d), distance_to_segment(b, c, d), distance_to_segment(c, a, b),
                   distance_to_segment(d, a, b)});
}

double distance_to_outline(const std::vector<Vec2>& poly, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < poly.size(); ++k)
    best = std::min(best, distance_to_segment(p, poly[k], poly[(k + 1) % poly.size()]));
  return best;
}

struct Box {
  Vec2 lo, hi;
  static Box of(const std::vector<Vec2>& pts) {
    Box b{pts[0], pts[0]};
    for (const Vec2& p : pts) {
      b.lo = b.lo.cwiseMin(p);
      b.hi = b.hi.cwiseMax(p);
    }
    return b;
  }
  bool contains(const Vec2& p, double pad = 0) const {
    return p.x() >= lo.x() - pad && p.x() <= hi.x() + pad && p.y() >= lo.y() - pad && p.y() <= hi.y() + pad;
  }
  bool overlaps(const Box& o, double pad) const {
    return lo.x() <= o.hi.x() + pad && o.lo.x() <= hi.x() + pad && lo.y() <= o.hi.y() + pad && o.lo.y() <= hi.y() + pad;
  }
};

std::string point_text(const Vec2& p) { return msg("(", p.x(), ", ", p.y(), ")"); }

// validate_simple_polygon, but a crossing is reported as such first: a
// symmetric bow tie has zero net area, and "zero area" would hide the cause.
void validate_outline(const std::vector<Vec2>& v, const std::string& what) {
  const std::size_t n = v.size();
  if (n >= 4 && std::all_of(v.begin(), v.end(), finite))
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 2; j < n; ++j) {
        if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
        if (segments_cross_properly(v[i], v[(i + 1) % n], v[j], v[(j + 1) % n]))
          throw Error(msg(what, ": polygon is self-intersecting (edges ", i + 1, " and ", j + 1, " cross)"));
      }
  validate_simple_polygon(v, what);
}

// The validated, oriented input.
struct Prepared {
  std::vector<Vec2> domain;              // counter-clockwise
  std::vector<std::vector<Vec2>> holes;  // counter-clockwise
  std::vector<Box> hole_boxes;
  Box box;
  double size = 0;  // larger side of the domain's bounding box
  double tol = 0;
  double expected_area = 0;
};

Prepared prepare(const CutInput& in) {
  Prepared p;
  if (in.domain.empty()) throw Error("domain: no outline given");
  validate_outline(in.domain, "domain");
  p.domain = in.domain;
  make_counter_clockwise(p.domain);
  p.box = Box::of(p.domain);
  p.size = std::max(p.box.hi.x() - p.box.lo.x(), p.box.hi.y() - p.box.lo.y());
  if (!std::isfinite(p.size) || !(p.size > 0)) throw Error("domain: the outline has no finite extent");

  if (!std::isfinite(in.snap_tolerance) || in.snap_tolerance < 0)
    throw Error(msg("snap tolerance must be a finite length ≥ 0, got ", in.snap_tolerance));
  if (in.snap_tolerance > kMaxRelativeSnap * p.size)
    throw Error(msg("snap tolerance ", in.snap_tolerance, " is too large for a domain of size ", p.size, " (at most ",
                    kMaxRelativeSnap, " × the size)"));
  p.tol = in.snap_tolerance > 0 ? in.snap_tolerance : 1e-9 * p.size;
  const double tol = p.tol;

  if (!std::isfinite(in.min_block_area) || in.min_block_area < 0)
    throw Error(msg("minimum block area must be a finite area ≥ 0, got ", in.min_block_area));
  if (in.default_rock_material < 0)
    throw Error(msg("default rock material must be ≥ 0, got ", in.default_rock_material));
  if (in.inner_cut_material < -1)
    throw Error(msg("inner cut material must be a joint material ≥ 0, or -1 to report inner loops, got ",
                    in.inner_cut_material));

  p.expected_area = signed_area(p.domain);
  for (std::size_t h = 0; h < in.holes.size(); ++h) {
    const std::string what = msg("hole ", h + 1);
    validate_outline(in.holes[h], what);
    std::vector<Vec2> hole = in.holes[h];
    make_counter_clockwise(hole);
    for (std::size_t k = 0; k < hole.size(); ++k) {
      if (!point_in_polygon(p.domain, hole[k]))
        throw Error(msg(what, ": vertex ", k + 1, " at ", point_text(hole[k]), " lies outside the domain"));
      if (distance_to_outline(p.domain, hole[k]) <= tol)
        throw Error(msg(what, ": vertex ", k + 1, " at ", point_text(hole[k]),
                        " lies on the domain boundary; holes must lie strictly inside the domain"));
    }
    for (std::size_t i = 0; i < hole.size(); ++i)
      for (std::size_t j = 0; j < p.domain.size(); ++j)
        if (segment_distance(hole[i], hole[(i + 1) % hole.size()], p.domain[j], p.domain[(j + 1) % p.domain.size()]) <=
            tol)
          throw Error(
              msg(what, " crosses or touches the domain boundary (hole edge ", i + 1, ", domain edge ", j + 1, ")"));
    p.hole_boxes.push_back(Box::of(hole));
    p.expected_area -= signed_area(hole);
    p.holes.push_back(std::move(hole));
  }
  for (std::size_t a = 0; a < p.holes.size(); ++a)
    for (std::size_t b = a + 1; b < p.holes.size(); ++b) {
      if (!p.hole_boxes[a].overlaps(p.hole_boxes[b], tol)) continue;
      const auto &ha = p.holes[a], &hb = p.holes[b];
      for (std::size_t i = 0; i < ha.size(); ++i)
        for (std::size_t j = 0; j < hb.size(); ++j)
          if (segment_distance(ha[i], ha[(i + 1) % ha.size()], hb[j], hb[(j + 1) % hb.size()]) <= tol)
            throw Error(msg("holes ", a + 1, " and ", b + 1, " cross or touch (edges ", i + 1, " and ", j + 1,
                            "); merge them into one hole"));
      if (point_in_polygon(ha, hb[0]) || point_in_polygon(hb, ha[0]))
        throw Error(msg("holes ", a + 1, " and ", b + 1, " overlap (one lies inside the other)"));
    }

  for (std::size_t r = 0; r < in.regions.size(); ++r) {
    const std::string what = msg("material region ", r + 1);
    validate_outline(in.regions[r].polygon, what);
    if (in.regions[r].rock_material < 0)
      throw Error(msg(what, ": rock material must be ≥ 0, got ", in.regions[r].rock_material));
  }
  for (std::size_t l = 0; l < in.lines.size(); ++l) {
    const JointLine& line = in.lines[l];
    const std::string what = msg("joint line ", l + 1);
    if (!finite(line.a) || !finite(line.b)) throw Error(msg(what, ": an end point has a non-finite coordinate"));
    if (!finite(Vec2(line.b - line.a)))
      throw Error(msg(what, ": end points ", point_text(line.a), " and ", point_text(line.b),
                      " lie too far apart to compute with"));
    if ((line.b - line.a).norm() <= tol)
      throw Error(msg(what, ": zero length (end points ", point_text(line.a), " and ", point_text(line.b), ")"));
    if (line.joint_material < 0) throw Error(msg(what, ": joint material must be ≥ 0, got ", line.joint_material));
  }
  for (std::size_t s = 0; s < in.sets.size(); ++s) validate_joint_set(in.sets[s], static_cast<int>(s), p.size);
  return p;
}

// ---- Segments -----------------------------------------------------------------

// What an arrangement edge is, by the input segment it came from.
struct SourceInfo {
  EdgeTag tag;
  bool one_sided = false;  // a boundary: rock lies only to the left of the segment's direction
  bool inner_cut = false;  // an automatic cut (inner_cut_material)
};

struct SegmentList {
  std::vector<ArrangementSegment> segments;
  std::vector<SourceInfo> info;

  void add(const Vec2& a, const Vec2& b, int rank, int end_rank, const EdgeTag& tag, bool one_sided,
           bool inner_cut = false) {
    segments.push_back({a, b, rank, end_rank});
    info.push_back({tag, one_sided, inner_cut});
  }
};

// The part of [a, b] inside the box [lo, hi], for segments reaching very far
// out (b - a finite). Computed along the segment's dominant axis u, with
// the other coordinate from the slope (|slope| ≤ 1), so that no parameter
// t ≈ 0.5 ± 1e-300 loses the part inside. False when no part lies inside.
bool clip_far_segment(Vec2& a, Vec2& b, const Vec2& lo, const Vec2& hi) {
  const Vec2 d = b - a;
  const int u = std::abs(d.x()) >= std::abs(d.y()) ? 0 : 1, v = 1 - u;
  const double slope = d[v] / d[u];
  double u0 = std::max(lo[u], std::min(a[u], b[u])), u1 = std::min(hi[u], std::max(a[u], b[u]));
  if (slope != 0) {
    double ua = a[u] + (lo[v] - a[v]) / slope, ub = a[u] + (hi[v] - a[v]) / slope;
    if (ua > ub) std::swap(ua, ub);
    u0 = std::max(u0, ua);
    u1 = std::min(u1, ub);
  } else if (a[v] < lo[v] || a[v] > hi[v]) {
    return false;
  }
  if (!(u0 < u1)) return false;
  Vec2 p, q;
  p[u] = u0, p[v] = a[v] + (u0 - a[u]) * slope;
  q[u] = u1, q[v] = a[v] + (u1 - a[u]) * slope;
  if (a[u] > b[u]) std::swap(p, q);  // keep the direction
  a = p, b = q;
  return true;
}

// Input order sets precedence where segments overlap: the boundary first,
// then explicit joint lines, then automatic inner cuts, then sets in order.
SegmentList collect_segments(const CutInput& in, const Prepared& p, const std::vector<JointLine>& inner_cuts) {
  SegmentList list;
  const EdgeTag domain_tag{EdgeKind::Domain, -1, -1};
  for (std::size_t k = 0; k < p.domain.size(); ++k)  // counter-clockwise: rock on the left
    list.add(p.domain[k], p.domain[(k + 1) % p.domain.size()], kBoundaryRank, kCornerRank, domain_tag, true);
  for (std::size_t h = 0; h < p.holes.size(); ++h) {
    const auto& hole = p.holes[h];
    const EdgeTag hole_tag{EdgeKind::Hole, -1, static_cast<int>(h)};
    for (std::size_t k = 0; k < hole.size(); ++k)  // walked clockwise, so the rock is on the left
      list.add(hole[(k + 1) % hole.size()], hole[k], kBoundaryRank, kCornerRank, hole_tag, true);
  }
  const double margin = 0.01 * p.size + 10 * p.tol;
  for (const JointLine& line : in.lines) {
    // Parts outside the domain are dropped anyway. An end point very far off
    // (fuzzing found 1e308) would overflow the arrangement's grid of cells:
    // such a line is clipped to the widened box first. Others go in as given.
    Vec2 a = line.a, b = line.b;
    const Vec2 lo = p.box.lo.array() - margin, hi = p.box.hi.array() + margin;
    auto far = [&](const Vec2& q) { return ((q - p.box.lo).cwiseAbs().maxCoeff() > kFarLine * p.size); };
    if ((far(a) || far(b)) && !clip_far_segment(a, b, lo, hi)) continue;
    list.add(a, b, kJointRank, kJointRank, {EdgeKind::Joint, line.joint_material, -1}, false);
  }
  for (const JointLine& cut : inner_cuts)
    list.add(cut.a, cut.b, kJointRank, kJointRank, {EdgeKind::Joint, cut.joint_material, -1}, false, true);
  // Refuse early what would exhaust memory: two sets of total joint lengths
  // L1 and L2 at angle Δ cross about L1·L2·|sin Δ| / A times in a box of area A.
  std::vector<double> set_length(in.sets.size(), 0.0);
  for (std::size_t s = 0; s < in.sets.size(); ++s) {
    const EdgeTag tag{EdgeKind::Joint, in.sets[s].joint_material, -1};
    for (const JointSegment& j : joint_set_segments(in.sets[s], static_cast<int>(s), p.box.lo, p.box.hi, margin)) {
      list.add(j.a, j.b, kJointRank, kJointRank, tag, false);
      set_length[s] += (j.b - j.a).norm();
    }
  }
  const Vec2 wide = (p.box.hi - p.box.lo).array() + 2 * margin;
  double all_crossings = 0;
  for (std::size_t a = 0; a < in.sets.size(); ++a)
    for (std::size_t b = a + 1; b < in.sets.size(); ++b) {
      const double angle = deg_to_rad(in.sets[a].dip_deg - in.sets[b].dip_deg);
      const double crossings = set_length[a] * set_length[b] * std::abs(std::sin(angle)) / (wide.x() * wide.y());
      if (crossings > kMaxSetCrossings)
        throw Error(msg("joint sets ", a + 1, " and ", b + 1, " would cross about ", std::round(crossings),
                        " times (limit ", kMaxSetCrossings,
                        "): far more blocks than a model can run; check the spacings"));
      all_crossings += crossings;
    }
  // The cut's memory grows with the crossings: refuse before cutting what cannot fit.
  check_memory_need(kCutBytesPerCrossing * (all_crossings + static_cast<double>(list.segments.size())),
                    memory_headroom(), "cutting the domain",
                    msg("about ", std::round(all_crossings), " joint crossings"),
                    "use larger joint spacings or a smaller domain");
  return list;
}

// ---- Planar graph and its faces ---------------------------------------------------

// The arrangement as a half-edge structure: half-edge 2e runs along edge e
// from `from` to `to`, 2e+1 back. Faces are traced with the face on the left,
// so blocks come out counter-clockwise and the outer boundary of every
// connected piece (seen from the face around it) clockwise.
class PlanarGraph {
 public:
  struct Face {
    int first = -1;  // a half-edge of the face
    int size = 0;
    double area = 0;  // signed: > 0 a block outline, < 0 an inner loop
    double perimeter = 0;
  };

  PlanarGraph(const Arrangement& arr, const std::vector<SourceInfo>& info) : v_(arr.vertices), info_(info) {
    const std::size_t n = arr.edges.size();
    from_.resize(n);
    to_.resize(n);
    source_.resize(n);
    alive_.assign(n, 1);
    for (std::size_t e = 0; e < n; ++e) {
      from_[e] = arr.edges[e].from;
      to_[e] = arr.edges[e].to;
      source_[e] = arr.edges[e].source;
    }
  }

  int edge_count() const { return static_cast<int>(from_.size()); }
  int vertex_count() const { return static_cast<int>(v_.size()); }
  bool alive(int e) const { return alive_[e] != 0; }
  void kill(int e) { alive_[e] = 0; }
  bool one_sided(int e) const { return info_[source_[e]].one_sided; }
  bool inner_cut(int e) const { return info_[source_[e]].inner_cut; }
  const EdgeTag& tag(int e) const { return info_[source_[e]].tag; }
  const Vec2& pos(int vtx) const { return v_[vtx]; }
  int origin(int h) const { return (h & 1) ? to_[h >> 1] : from_[h >> 1]; }
  int head(int h) const { return (h & 1) ? from_[h >> 1] : to_[h >> 1]; }
  // Half-edges with rock on their left: both sides of a joint, the inner side of a boundary.
  bool rock(int h) const { return alive_[h >> 1] && (!one_sided(h >> 1) || (h & 1) == 0); }
  Vec2 midpoint(int e) const { return 0.5 * (v_[from_[e]] + v_[to_[e]]); }
  double length(int e) const { return (v_[to_[e]] - v_[from_[e]]).norm(); }
  int next(int h) const { return next_[h]; }
  int face_of(int h) const { return face_[h]; }
  const std::vector<Face>& faces() const { return faces_; }

  int vertices_in_use() const {
    std::vector<char> used(v_.size(), 0);
    for (int e = 0; e < edge_count(); ++e)
      if (alive_[e]) used[from_[e]] = used[to_[e]] = 1;
    return static_cast<int>(std::count(used.begin(), used.end(), 1));
  }

  // Tree cutting (as in Shi's block-cutting program): removes, repeatedly,
  // every edge with an end point that no other edge reaches. What is left
  // closes blocks. Returns the number of edges removed.
  int remove_dangling() {
    std::vector<int> degree(v_.size(), 0);
    std::vector<int> start(v_.size() + 1, 0);
    for (int e = 0; e < edge_count(); ++e)
      if (alive_[e]) {
        ++degree[from_[e]];
        ++degree[to_[e]];
        ++start[from_[e] + 1];
        ++start[to_[e] + 1];
      }
    for (std::size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
    std::vector<int> incident(start.back());
    {
      std::vector<int> fill(start.begin(), start.end() - 1);
      for (int e = 0; e < edge_count(); ++e)
        if (alive_[e]) {
          incident[fill[from_[e]]++] = e;
          incident[fill[to_[e]]++] = e;
        }
    }
    std::vector<int> stack;
    for (int vtx = 0; vtx < static_cast<int>(v_.size()); ++vtx)
      if (degree[vtx] == 1) stack.push_back(vtx);
    int removed = 0;
    while (!stack.empty()) {
      const int vtx = stack.back();
      stack.pop_back();
      if (degree[vtx] != 1) continue;
      for (int k = start[vtx]; k < start[vtx + 1]; ++k) {
        const int e = incident[k];
        if (!alive_[e]) continue;
        alive_[e] = 0;
        ++removed;
        const int other = from_[e] == vtx ? to_[e] : from_[e];
        --degree[vtx];
        if (--degree[other] == 1) stack.push_back(other);
        break;
      }
    }
    return removed;
  }

  // Sorts the half-edges round each vertex by angle and traces every face
  // bounded by rock half-edges.
  void trace() {
    const int nh = 2 * edge_count();
    std::vector<int> start(v_.size() + 1, 0);
    for (int h = 0; h < nh; ++h)
      if (alive_[h >> 1]) ++start[origin(h) + 1];
    for (std::size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
    std::vector<int> around(start.back());
    std::vector<double> angle(nh, 0);
    {
      std::vector<int> fill(start.begin(), start.end() - 1);
      for (int h = 0; h < nh; ++h)
        if (alive_[h >> 1]) {
          const Vec2 d = v_[head(h)] - v_[origin(h)];
          angle[h] = std::atan2(d.y(), d.x());
          around[fill[origin(h)]++] = h;
        }
    }
    std::vector<int> slot(nh, -1);
    for (std::size_t vtx = 0; vtx < v_.size(); ++vtx) {
      auto b = around.begin() + start[vtx], e = around.begin() + start[vtx + 1];
      std::sort(b, e, [&](int x, int y) { return angle[x] != angle[y] ? angle[x] < angle[y] : x < y; });
      for (int k = start[vtx]; k < start[vtx + 1]; ++k) slot[around[k]] = k - start[vtx];
    }
    // Arriving at v along h, the face on the left continues along the
    // half-edge next clockwise from h's twin.
    next_.assign(nh, -1);
    for (int h = 0; h < nh; ++h) {
      if (!alive_[h >> 1]) continue;
      const int vtx = head(h);
      const int degree = start[vtx + 1] - start[vtx];
      next_[h] = around[start[vtx] + (slot[h ^ 1] + degree - 1) % degree];
    }
    face_.assign(nh, -1);
    faces_.clear();
    for (int h0 = 0; h0 < nh; ++h0) {
      if (!rock(h0) || face_[h0] >= 0) continue;
      Face f;
      f.first = h0;
      const int id = static_cast<int>(faces_.size());
      const Vec2 o = v_[origin(h0)];
      double twice = 0;
      int h = h0;
      do {
        if (!rock(h) || face_[h] >= 0 || f.size > nh)
          throw Error(
              "block cutting: internal error: inconsistent face (a face meets the outside of the "
              "domain); please report the input");
        face_[h] = id;
        twice += cross(v_[origin(h)] - o, v_[head(h)] - o);
        f.perimeter += length(h >> 1);
        ++f.size;
        h = next_[h];
      } while (h != h0);
      f.area = 0.5 * twice;
      faces_.push_back(f);
    }
  }

 private:
  const std::vector<Vec2>& v_;
  const std::vector<SourceInfo>& info_;
  std::vector<int> from_, to_, source_;
  std::vector<char> alive_;
  std::vector<int> next_, face_;
  std::vector<Face> faces_;
};

// Union-find over faces, for merging slivers.
struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// The first point where the ray p + t·dir (t > 0) meets an alive edge that
// `skip(e)` does not exclude.
template <typename Skip>
Vec2 first_hit(const PlanarGraph& g, const Vec2& p, const Vec2& dir, Skip&& skip) {
  double best = std::numeric_limits<double>::infinity();
  for (int e = 0; e < g.edge_count(); ++e) {
    if (!g.alive(e) || skip(e)) continue;
    const Vec2 &qa = g.pos(g.origin(2 * e)), &qb = g.pos(g.head(2 * e));
    const Vec2 q = qb - qa;
    const double denom = cross(dir, q);
    if (denom == 0) {
      if (cross(qa - p, dir) != 0) continue;  // parallel, off the ray
      for (const Vec2& end : {qa, qb}) {
        const double t = (end - p).dot(dir);
        if (t > 0 && t < best) best = t;
      }
      continue;
    }
    const double t = cross(qa - p, q) / denom;
    const double u = cross(qa - p, dir) / denom;
    if (u >= 0 && u <= 1 && t > 0 && t < best) best = t;
  }
  if (!std::isfinite(best))
    throw Error("block cutting: internal error: a cut from an inner loop met no edge; please report the input");
  return p + best * dir;
}

// The ray from vertex `vtx` along an axis (0: x, 1: y) towards `sign`.
Vec2 axis_ray_hit(const PlanarGraph& g, int vtx, int axis, double sign) {
  Vec2 dir = Vec2::Zero();
  dir[axis] = sign;
  Vec2 hit = first_hit(g, g.pos(vtx), dir, [&](int e) { return g.origin(2 * e) == vtx || g.head(2 * e) == vtx; });
  hit[1 - axis] = g.pos(vtx)[1 - axis];  // exactly axis-parallel
  return hit;
}

// Where a cut from an inner loop starts: the loop's extreme vertex in the
// direction (axis, sign); among equally extreme vertices one that is not a
// pinch vertex, then the one furthest along the other axis. The ray from an
// extreme vertex outwards leaves the loop's hull at once, into the block
// around it.
template <typename IsPinch>
int extreme_vertex(const PlanarGraph& g, const std::vector<int>& loop, int axis, double sign, IsPinch&& is_pinch) {
  int best = -1;
  for (int v : loop) {
    if (best < 0) {
      best = v;
      continue;
    }
    const Vec2 &p = g.pos(v), &q = g.pos(best);
    const double ahead = sign * (p[axis] - q[axis]);
    const bool better_tie = is_pinch(best) != is_pinch(v) ? is_pinch(best) : sign * (p[1 - axis] - q[1 - axis]) > 0;
    if (ahead > 0 || (ahead == 0 && better_tie)) best = v;
  }
  return best;
}

// Reports, or cuts free, the inner loops of the traced faces: pieces of the
// arrangement that float inside a block (a hole no joint reaches, an isolated
// loop of joints) and need two cuts, and pieces that touch the surrounding
// block at a single vertex (a "pinch": the block's outline would pass twice
// through one point) and need one. Returns the cuts to add; throws if
// cutting is not allowed.
std::vector<JointLine> inner_loop_cuts(const PlanarGraph& g, const CutInput& in) {
  std::vector<JointLine> cuts;
  auto hole_of = [&](const std::vector<int>& half_edges) {
    for (int h : half_edges)
      if (g.tag(h >> 1).kind == EdgeKind::Hole) return g.tag(h >> 1).hole;
    return -1;
  };
  auto refuse = [&](int hole, const Vec2& where, bool pinched) {
    const std::string fix =
        ", which DDA cannot represent. Add joints that reach it, or set inner_cut_material to "
        "cut it free automatically";
    const std::string twice = pinched ? " (its outline passing twice through one point)" : "";
    if (hole >= 0)
      throw Error(msg("hole ", hole + 1,
                      pinched ? msg(" touches the joints only at the point ", point_text(where))
                              : std::string(" is not reached by any joint"),
                      ": the rock around it would be a block with a hole", twice, fix));
    throw Error(msg("a closed loop of joints near ", point_text(where),
                    pinched ? std::string(" touches the other joints only at that point")
                            : std::string(" touches no other joint or boundary"),
                    ": the block around it would have a hole", twice, fix));
  };
  auto add_cut = [&](int vertex, int axis, double sign) {
    cuts.push_back({g.pos(vertex), axis_ray_hit(g, vertex, axis, sign), in.inner_cut_material});
  };
  auto vertices_of = [&](const std::vector<int>& half_edges) {
    std::vector<int> v;
    for (int h : half_edges) v.push_back(g.origin(h));
    return v;
  };

  std::vector<int> slot(g.vertex_count(), -1);   // vertex → position on the walk stack
  std::vector<char> pinch(g.vertex_count(), 0);  // vertex visited twice by the current face
  std::vector<int> walk, stack;
  std::vector<std::vector<int>> loops;
  for (const PlanarGraph::Face& f : g.faces()) {
    walk.clear();
    int h = f.first;
    do {
      walk.push_back(h);
      h = g.next(h);
    } while (h != f.first);

    if (f.area < 0) {  // a loop floating inside a block: cut it free on both sides
      const std::vector<int> loop = vertices_of(walk);
      auto none = [](int) { return false; };
      const int right = extreme_vertex(g, loop, 0, +1, none);
      if (in.inner_cut_material < 0) refuse(hole_of(walk), g.pos(right), false);
      add_cut(right, 0, +1);
      add_cut(extreme_vertex(g, loop, 0, -1, none), 0, -1);
      continue;
    }

    // A block outline through a vertex twice: split the walk into simple
    // loops at repeated vertices. The counter-clockwise loop is the block's
    // outline; clockwise ones go round pieces attached at one point.
    loops.clear();
    stack.clear();
    for (int e : walk) {
      const int v = g.origin(e);
      if (slot[v] >= 0) {
        const int from = slot[v];
        pinch[v] = 1;
        loops.emplace_back(stack.begin() + from, stack.end());
        for (std::size_t k = from; k < stack.size(); ++k) slot[g.origin(stack[k])] = -1;
        stack.resize(from);
      }
      slot[v] = static_cast<int>(stack.size());
      stack.push_back(e);
    }
    for (int e : stack) slot[g.origin(e)] = -1;
    if (loops.empty()) continue;
    loops.push_back(stack);  // what is left closes at the walk's start
    for (const std::vector<int>& loop : loops) {
      double twice = 0;
      const Vec2 o = g.pos(g.origin(loop[0]));
      for (int e : loop) twice += cross(g.pos(g.origin(e)) - o, g.pos(g.head(e)) - o);
      if (twice >= 0) continue;
      const std::vector<int> lv = vertices_of(loop);
      auto is_pinch = [&](int v) { return pinch[v] != 0; };
      int at = -1;
      for (int v : lv)
        if (pinch[v]) at = v;
      if (in.inner_cut_material < 0) refuse(hole_of(loop), g.pos(at), true);
      // One cut, from an extreme vertex that is not where the loop is
      // attached: right, else left, up or down.
      bool cut = false;
      for (const auto& [axis, sign] : {std::pair{0, 1.0}, std::pair{0, -1.0}, std::pair{1, 1.0}, std::pair{1, -1.0}}) {
        const int start = extreme_vertex(g, lv, axis, sign, is_pinch);
        if (pinch[start]) continue;
        add_cut(start, axis, sign);
        cut = true;
        break;
      }
      if (!cut) {
        // Every extreme vertex is itself a pinch (loops hanging from loops):
        // cut from the middle of the loop's longest edge, square to it, into
        // the block.
        int longest = loop[0];
        for (int e : loop)
          if (g.length(e >> 1) > g.length(longest >> 1)) longest = e;
        const Vec2 a = g.pos(g.origin(longest)), b = g.pos(g.head(longest));
        const Vec2 mid = 0.5 * (a + b);
        const Vec2 inward = Vec2(-(b - a).y(), (b - a).x()).normalized();  // the block lies to the left
        cuts.push_back(
            {mid, first_hit(g, mid, inward, [&](int e) { return e == (longest >> 1); }), in.inner_cut_material});
      }
    }
    for (int e : walk) pinch[g.origin(e)] = 0;
  }
  return cuts;
}

// Merges every block below the minimum area (and every degenerate one, thinner
// than the snap tolerance) into the neighbour sharing the longest boundary
// with it, by removing the joints between them. Returns the number merged;
// throws under SliverPolicy::Error or when a sliver has no neighbour.
int merge_slivers(PlanarGraph& g, const CutInput& in, double tol) {
  const auto& faces = g.faces();
  const int nf = static_cast<int>(faces.size());
  DisjointSets sets(nf);
  int merged = 0;
  std::vector<std::string> reported;
  int reported_count = 0;
  std::vector<double> shared(nf, 0);
  std::vector<int> touched;
  for (int f = 0; f < nf; ++f) {
    const PlanarGraph::Face& face = faces[f];
    if (face.area < 0) continue;
    // Thinner on average (2 × area / perimeter) than 8 snap tolerances: an
    // artefact of nearly coincident joints, merged whatever the policy.
    const bool degenerate = face.area <= 4 * tol * face.perimeter;
    if (!degenerate && !(face.area < in.min_block_area)) continue;

    // Centroid-ish point for messages: the first vertex is enough to find it.
    const Vec2 where = g.pos(g.origin(face.first));
    if (!degenerate && in.sliver_policy == SliverPolicy::Error) {
      if (reported_count++ < 5) reported.push_back(msg("area ", face.area, " at ", point_text(where)));
      continue;
    }
    // Across an automatic cut only if nothing else is shared: merging across
    // it would undo the cut and bring back the loop it cut free.
    int best = -1;
    for (const bool across_cuts : {false, true}) {
      touched.clear();
      int h = face.first;
      do {
        const int e = h >> 1;
        const int other = g.face_of(h ^ 1);
        if (!g.one_sided(e) && (across_cuts || !g.inner_cut(e)) && other >= 0 && other != f && faces[other].area > 0) {
          if (shared[other] == 0) touched.push_back(other);
          shared[other] += g.length(e);
        }
        h = g.next(h);
      } while (h != face.first);
      for (int o : touched) {
        if (best < 0 || shared[o] > shared[best] || (shared[o] == shared[best] && o < best)) best = o;
      }
      for (int o : touched) shared[o] = 0;
      if (best >= 0) break;
    }
    if (best < 0)
      throw Error(msg("a block of area ", face.area, " at ", point_text(where),
                      " is below the minimum block area but shares no joint with another block to merge into"));
    sets.join(f, best);
    ++merged;
  }
  if (reported_count > 0) {
    std::string list;
    for (const std::string& r : reported) list += "\n  " + r;
    throw Error(msg(reported_count, " block(s) smaller than the minimum block area ", in.min_block_area,
                    " (sliver policy: error):", list, reported_count > 5 ? "\n  ..." : ""));
  }
  if (merged == 0) return 0;
  for (int e = 0; e < g.edge_count(); ++e) {
    if (!g.alive(e) || g.one_sided(e)) continue;
    const int a = g.face_of(2 * e), b = g.face_of(2 * e + 1);
    if (a >= 0 && b >= 0 && sets.find(a) == sets.find(b)) g.kill(e);
  }
  return merged;
}

// ---- Blocks -------------------------------------------------------------------------

// Is v a straight-on vertex between u and w (within tol of the chord, and
// not a spike back)?
bool goes_straight(const Vec2& u, const Vec2& v, const Vec2& w, double tol) {
  const Vec2 uw = w - u;
  return std::abs(cross(uw, v - u)) <= tol * uw.norm() && (v - u).dot(w - v) > 0;
}

// The outline of face f with only its true corners. Returns the signed area
// removed with straight-on vertices: zero to rounding, unless snapping bent a
// joint by up to the tolerance there.
double block_outline(const PlanarGraph& g, const PlanarGraph::Face& face, double tol, CutBlock& block) {
  std::vector<Vec2> pts;
  std::vector<EdgeTag> tags;
  pts.reserve(face.size);
  tags.reserve(face.size);
  int h = face.first;
  do {
    pts.push_back(g.pos(g.origin(h)));
    tags.push_back(g.tag(h >> 1));
    h = g.next(h);
  } while (h != face.first);

  const int n = static_cast<int>(pts.size());
  std::vector<int> prev(n), next(n);
  for (int k = 0; k < n; ++k) {
    prev[k] = (k + n - 1) % n;
    next[k] = (k + 1) % n;
  }
  std::vector<char> removed(n, 0);
  std::vector<int> work(n);
  std::iota(work.rbegin(), work.rend(), 0);  // pop from the back: vertex 0 first
  int remaining = n;
  double removed_area = 0;
  while (!work.empty() && remaining > 3) {
    const int k = work.back();
    work.pop_back();
    if (removed[k]) continue;
    const int p = prev[k], q = next[k];
    // A vertex where the edge tag changes stays: loads and boundary
    // conditions attach to edges by tag.
    if (!(tags[p] == tags[k]) || !goes_straight(pts[p], pts[k], pts[q], tol)) continue;
    removed_area += 0.5 * cross(pts[k] - pts[p], pts[q] - pts[p]);
    removed[k] = 1;
    next[p] = q;
    prev[q] = p;
    --remaining;
    work.push_back(p);
    work.push_back(q);
  }
  int k0 = 0;
  while (removed[k0]) ++k0;
  block.vertices.clear();
  block.edges.clear();
  int k = k0;
  do {
    block.vertices.push_back(pts[k]);
    block.edges.push_back(tags[k]);
    k = next[k];
  } while (k != k0);
  return removed_area;
}

}  // namespace

// ---- cut_blocks ---------------------------------------------------------------------

BlockSet cut_blocks(const CutInput& in) {
  const Prepared p = prepare(in);
  const double tol = p.tol;

  BlockSet out;
  out.snap_tolerance = tol;
  out.expected_area = p.expected_area;
  out.hole_count = static_cast<int>(p.holes.size());

  std::vector<JointLine> inner_cuts;
  double removed_area = 0;  // cut off with straight-on vertices; rounding-sized
  for (int pass = 0;; ++pass) {
    const SegmentList segs = collect_segments(in, p, inner_cuts);
    const Arrangement arr = build_arrangement(segs.segments, tol);
    PlanarGraph g(arr, segs.info);

    // Joints outside the domain or inside a hole go. Every joint edge now
    // ends at a boundary crossing or inside the rock, so its midpoint is
    // clearly on one side.
    for (int e = 0; e < g.edge_count(); ++e) {
      if (g.one_sided(e)) continue;
      const Vec2 m = g.midpoint(e);
      bool rock = point_in_polygon(p.domain, m);
      for (std::size_t h = 0; rock && h < p.holes.size(); ++h)
        if (p.hole_boxes[h].contains(m) && point_in_polygon(p.holes[h], m)) rock = false;
      if (!rock) g.kill(e);
    }
    CutStats stats;
    stats.input_segments = static_cast<int>(segs.segments.size());
    stats.arrangement_rounds = arr.rounds;
    stats.vertices = g.vertices_in_use();
    for (int e = 0; e < g.edge_count(); ++e) stats.edges += g.alive(e) ? 1 : 0;
    stats.inner_cuts = static_cast<int>(inner_cuts.size());

    // Clean up until every face is a simply connected block above the
    // minimum area: dangling joints, bridges (a joint with the same block on
    // both sides), inner loops, slivers.
    std::vector<JointLine> new_cuts;
    for (int round = 0;; ++round) {
      if (round == kMaxCleanupPasses)
        throw Error("block cutting: slivers kept appearing while merging; check min_block_area");
      stats.dangling_edges_removed += g.remove_dangling();
      g.trace();
      int bridges = 0;
      for (int e = 0; e < g.edge_count(); ++e)
        if (g.alive(e) && !g.one_sided(e) && g.face_of(2 * e) == g.face_of(2 * e + 1)) {
          g.kill(e);
          ++bridges;
        }
      if (bridges > 0) {
        stats.dangling_edges_removed += bridges;
        continue;
      }
      new_cuts = inner_loop_cuts(g, in);
      if (!new_cuts.empty()) break;
      const int merged = merge_slivers(g, in, tol);
      stats.slivers_merged += merged;
      if (merged == 0) break;
    }
    if (!new_cuts.empty()) {
      if (pass + 1 == kMaxInnerCutPasses)
        throw Error("block cutting: inner loops remained after automatic cuts; connect them with joint lines");
      inner_cuts.insert(inner_cuts.end(), new_cuts.begin(), new_cuts.end());
      continue;
    }

    // Faces → blocks.
    for (const PlanarGraph::Face& f : g.faces()) {
      if (f.area < 0) continue;
      CutBlock block;
      removed_area += block_outline(g, f, tol, block);
      const PolygonMoments m = polygon_moments(block.vertices);
      block.area = m.area;
      block.centroid = m.centroid;
      block.rock_material = in.default_rock_material;
      for (const MaterialRegion& region : in.regions)
        if (point_in_polygon(region.polygon, block.centroid)) block.rock_material = region.rock_material;
      out.blocks.push_back(std::move(block));
    }
    out.stats = stats;
    break;
  }

  // Reading order: rows from the bottom, left to right (centroids quantised
  // to the tolerance, so blocks of one row sort by x).
  std::vector<std::pair<std::pair<long long, long long>, int>> order;
  order.reserve(out.blocks.size());
  for (int b = 0; b < static_cast<int>(out.blocks.size()); ++b) {
    const Vec2 c = (out.blocks[b].centroid - p.box.lo) / tol;
    order.push_back({{std::llround(c.y()), std::llround(c.x())}, b});
  }
  std::sort(order.begin(), order.end());
  std::vector<CutBlock> sorted;
  sorted.reserve(out.blocks.size());
  for (const auto& o : order) sorted.push_back(std::move(out.blocks[o.second]));
  out.blocks = std::move(sorted);

  // The blocks must tile the domain minus the holes.
  const double total = out.total_area();
  if (!(std::abs(total + removed_area - p.expected_area) <= 1e-9 * p.expected_area))
    throw Error(msg("block cutting: internal error: the blocks' areas sum to ", total, ", the domain minus holes is ",
                    p.expected_area, "; please report the input"));
  return out;
}

// ---- Queries -------------------------------------------------------------------------

namespace {

bool in_box(const Vec2& p, const Vec2& lo, const Vec2& hi) {
  return p.x() >= lo.x() && p.x() <= hi.x() && p.y() >= lo.y() && p.y() <= hi.y();
}

// Does the segment [a, b] meet the closed box?
bool segment_meets_box(const Vec2& a, const Vec2& b, const Vec2& lo, const Vec2& hi) {
  double t0 = 0, t1 = 1;
  const Vec2 d = b - a;
  for (int axis = 0; axis < 2; ++axis) {
    if (d[axis] == 0) {
      if (a[axis] < lo[axis] || a[axis] > hi[axis]) return false;
      continue;
    }
    double ta = (lo[axis] - a[axis]) / d[axis], tb = (hi[axis] - a[axis]) / d[axis];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

std::vector<int> BlockSet::blocks_containing(const Vec2& p, double tol) const {
  if (tol < 0) tol = snap_tolerance;
  std::vector<int> found;
  for (int b = 0; b < static_cast<int>(blocks.size()); ++b) {
    const auto& v = blocks[b].vertices;
    const Box box = Box::of(v);
    if (!box.contains(p, tol)) continue;
    if (point_in_polygon(v, p) || distance_to_outline(v, p) <= tol) found.push_back(b);
  }
  return found;
}

std::vector<int> BlockSet::blocks_in_box(const Vec2& box_lo, const Vec2& box_hi, BoxSelect mode) const {
  // Widened by the snap tolerance: a box drawn along joints takes the blocks
  // on its edges whatever the rounding of their vertices.
  const Vec2 lo = box_lo.array() - snap_tolerance, hi = box_hi.array() + snap_tolerance;
  std::vector<int> found;
  for (int b = 0; b < static_cast<int>(blocks.size()); ++b) {
    const CutBlock& block = blocks[b];
    bool take = false;
    switch (mode) {
      case BoxSelect::Centroid:
        take = in_box(block.centroid, lo, hi);
        break;
      case BoxSelect::Inside:
        take =
            std::all_of(block.vertices.begin(), block.vertices.end(), [&](const Vec2& v) { return in_box(v, lo, hi); });
        break;
      case BoxSelect::Overlap: {
        const Box box = Box::of(block.vertices);
        if (!box.overlaps(Box{lo, hi}, 0)) break;
        // An edge meets the box, or the box lies wholly inside the block.
        const std::size_t n = block.vertices.size();
        for (std::size_t k = 0; k < n && !take; ++k)
          take = segment_meets_box(block.vertices[k], block.vertices[(k + 1) % n], lo, hi);
        if (!take) take = point_in_polygon(block.vertices, 0.5 * (lo + hi));
        break;
      }
    }
    if (take) found.push_back(b);
  }
  return found;
}

std::vector<EdgeRef> BlockSet::edges_on_segment(const Vec2& a, const Vec2& b, double tol) const {
  if (tol < 0) tol = snap_tolerance;
  std::vector<EdgeRef> found;
  for (int bl = 0; bl < static_cast<int>(blocks.size()); ++bl) {
    const auto& v = blocks[bl].vertices;
    for (int k = 0; k < static_cast<int>(v.size()); ++k)
      if (distance_to_segment(v[k], a, b) <= tol && distance_to_segment(v[(k + 1) % v.size()], a, b) <= tol)
        found.push_back({bl, k});
  }
  return found;
}

std::vector<EdgeRef> BlockSet::edges_in_box(const Vec2& box_lo, const Vec2& box_hi) const {
  const Vec2 lo = box_lo.array() - snap_tolerance, hi = box_hi.array() + snap_tolerance;
  std::vector<EdgeRef> found;
  for (int bl = 0; bl < static_cast<int>(blocks.size()); ++bl) {
    const auto& v = blocks[bl].vertices;
    for (int k = 0; k < static_cast<int>(v.size()); ++k)
      if (in_box(v[k], lo, hi) && in_box(v[(k + 1) % v.size()], lo, hi)) found.push_back({bl, k});
  }
  return found;
}

std::vector<EdgeRef> BlockSet::domain_boundary_edges() const {
  std::vector<EdgeRef> found;
  for (int bl = 0; bl < static_cast<int>(blocks.size()); ++bl)
    for (int k = 0; k < static_cast<int>(blocks[bl].edges.size()); ++k)
      if (blocks[bl].edges[k].kind == EdgeKind::Domain) found.push_back({bl, k});
  return found;
}

std::vector<EdgeRef> BlockSet::hole_boundary_edges(int hole) const {
  if (hole < 0 || hole >= hole_count)
    throw Error(msg("hole ", hole + 1, " does not exist (the model has ", hole_count, " hole(s))"));
  std::vector<EdgeRef> found;
  for (int bl = 0; bl < static_cast<int>(blocks.size()); ++bl)
    for (int k = 0; k < static_cast<int>(blocks[bl].edges.size()); ++k) {
      const EdgeTag& t = blocks[bl].edges[k];
      if (t.kind == EdgeKind::Hole && t.hole == hole) found.push_back({bl, k});
    }
  return found;
}

std::pair<Vec2, Vec2> BlockSet::edge_points(EdgeRef e) const {
  const auto& v = blocks.at(e.block).vertices;
  return {v.at(e.edge), v[(e.edge + 1) % v.size()]};
}

double BlockSet::edge_length(EdgeRef e) const {
  const auto [a, b] = edge_points(e);
  return (b - a).norm();
}

double BlockSet::total_area() const {
  double sum = 0;
  for (const CutBlock& b : blocks) sum += b.area;
  return sum;
}

}  // namespace dda::geometry
