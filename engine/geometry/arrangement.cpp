// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "geometry/arrangement.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/error.hpp"
#include "geometry/polygon.hpp"

namespace dda::geometry {
namespace {

// A segment between two points of the current round's point array.
struct Seg {
  int pa, pb;
  int rank;
  int source;
};

// "Point `point` lies on segment `seg`": the segment is split there.
struct Split {
  int seg;
  int point;
};

// "End point `end` was moved onto a segment, to point `foot`": whatever
// vertex the foot snaps to, the end point must snap to the same one.
struct Moved {
  int end;
  int foot;
};

struct Round {
  std::vector<Vec2> pos;
  // Snapping priority per point: 2 × the rank of the segment that placed it,
  // plus 1 for a point projected onto a segment (a T-junction), so that the
  // projected copy wins over the loose end point it was made from.
  std::vector<int> rank;
  std::vector<Seg> segs;
};

int end_priority(int rank) { return 2 * rank; }
int foot_priority(int rank) { return 2 * rank + 1; }

// Distance from p to the closed segment [a, b]; `foot` receives the nearest point.
double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b, Vec2& foot) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  double t = len2 > 0 ? (p - a).dot(ab) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  foot = a + t * ab;
  return (p - foot).norm();
}

// Limits no usable DDA model comes near (tens of millions of blocks), so that
// a typo in a spacing gives an error instead of exhausting memory.
constexpr std::size_t kMaxGridEntries = 200'000'000;
constexpr std::size_t kMaxSplits = 20'000'000;

// ---- Broad phase ------------------------------------------------------------

// Uniform grid over the segments' bounding box. Each segment is registered in
// every cell its tol-neighbourhood touches, so two segments that come within
// tol of each other always share a cell.
class SegmentGrid {
 public:
  SegmentGrid(const Round& r, double tol) : r_(r), tol_(tol) {
    Vec2 lo(std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
    Vec2 hi = -lo;
    for (const Seg& s : r.segs) {
      lo = lo.cwiseMin(r.pos[s.pa]).cwiseMin(r.pos[s.pb]);
      hi = hi.cwiseMax(r.pos[s.pa]).cwiseMax(r.pos[s.pb]);
    }
    lo.array() -= 2 * tol;
    hi.array() += 2 * tol;
    origin_ = lo;
    const double w = hi.x() - lo.x(), h = hi.y() - lo.y();
    const double n = std::max<double>(1.0, static_cast<double>(r.segs.size()));
    // About one segment per cell on average; for a thin box (all segments on a
    // line) fall back to the long side divided among the segments.
    const double area = std::max(w * h, std::max(w, h) * std::max(w, h) / n);
    cell_ = std::max(std::sqrt(area / n), 4 * tol);
    nx_ = static_cast<int>(std::clamp(std::ceil(w / cell_), 1.0, 32768.0));
    ny_ = static_cast<int>(std::clamp(std::ceil(h / cell_), 1.0, 32768.0));
    // Keep the cell count proportional to the segment count.
    while (static_cast<double>(nx_) * ny_ > 4 * n + 64) {
      cell_ *= 1.5;
      nx_ = static_cast<int>(std::clamp(std::ceil(w / cell_), 1.0, 32768.0));
      ny_ = static_cast<int>(std::clamp(std::ceil(h / cell_), 1.0, 32768.0));
    }
    // Counting sort of (cell, segment) entries into CSR arrays.
    start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
    for (int s = 0; s < static_cast<int>(r.segs.size()); ++s) for_each_cell(s, [&](std::size_t c) { ++start_[c + 1]; });
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    if (start_.back() > kMaxGridEntries)
      throw Error(msg("block cutting: the joints are too many or too dense to cut (", r.segs.size(),
                      " segments); check the joint spacings and trace lengths"));
    entries_.resize(start_.back());
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (int s = 0; s < static_cast<int>(r.segs.size()); ++s)
      for_each_cell(s, [&](std::size_t c) { entries_[fill[c]++] = s; });
  }

  // Calls f(i, j) once for every pair i < j sharing a cell, in ascending
  // order of (i, j). Each segment gathers its partners from its own cells
  // and sorts that short list, which is much cheaper than sorting all pairs.
  template <typename F>
  void for_each_candidate_pair(F&& f) const {
    std::vector<int> partners;
    for (int i = 0; i < static_cast<int>(r_.segs.size()); ++i) {
      partners.clear();
      for_each_cell(i, [&](std::size_t c) {
        // Entries of a cell are in ascending segment order: take those after i.
        auto b = entries_.begin() + static_cast<std::ptrdiff_t>(start_[c]);
        auto e = entries_.begin() + static_cast<std::ptrdiff_t>(start_[c + 1]);
        partners.insert(partners.end(), std::upper_bound(b, e, i), e);
      });
      std::sort(partners.begin(), partners.end());
      partners.erase(std::unique(partners.begin(), partners.end()), partners.end());
      for (int j : partners) f(i, j);
    }
  }

 private:
  int column(double x) const {
    return static_cast<int>(std::clamp(std::floor((x - origin_.x()) / cell_), 0.0, nx_ - 1.0));
  }
  int row(double y) const {
    return static_cast<int>(std::clamp(std::floor((y - origin_.y()) / cell_), 0.0, ny_ - 1.0));
  }

  template <typename F>
  void for_each_cell(int s, F&& f) const {
    const Vec2& a = r_.pos[r_.segs[s].pa];
    const Vec2& b = r_.pos[r_.segs[s].pb];
    const double xlo = std::min(a.x(), b.x()) - tol_, xhi = std::max(a.x(), b.x()) + tol_;
    const double dx = b.x() - a.x();
    const int c0 = column(xlo), c1 = column(xhi);
    for (int c = c0; c <= c1; ++c) {
      double ylo, yhi;
      if (c0 == c1 || dx == 0) {
        ylo = std::min(a.y(), b.y());
        yhi = std::max(a.y(), b.y());
      } else {
        // The part of the segment whose x lies in this column, widened by tol.
        const double x0 = origin_.x() + c * cell_ - tol_, x1 = origin_.x() + (c + 1) * cell_ + tol_;
        const double t0 = std::clamp((x0 - a.x()) / dx, 0.0, 1.0);
        const double t1 = std::clamp((x1 - a.x()) / dx, 0.0, 1.0);
        const double y0 = a.y() + t0 * (b.y() - a.y()), y1 = a.y() + t1 * (b.y() - a.y());
        ylo = std::min(y0, y1);
        yhi = std::max(y0, y1);
      }
      const int r0 = row(ylo - tol_), r1 = row(yhi + tol_);
      for (int rr = r0; rr <= r1; ++rr) f(static_cast<std::size_t>(rr) * nx_ + c);
    }
  }

  const Round& r_;
  double tol_;
  Vec2 origin_;
  double cell_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<std::size_t> start_;
  std::vector<int> entries_;
};

// ---- Narrow phase -----------------------------------------------------------

// Finds where segments i and j meet and records the splits. New points are
// appended to r.pos / r.rank.
void intersect_pair(Round& r, int i, int j, double tol, std::vector<Split>& splits, std::vector<Moved>& moved) {
  const Seg si = r.segs[i], sj = r.segs[j];
  bool touched = false;

  // An end point of another segment within tol of segment `k` splits k
  // there. Unless the point outranks the segment (a domain corner near a
  // joint), the split goes at the point's foot on k, so k stays straight and
  // the end point snaps to the foot: a joint ending on a boundary or on
  // another joint moves onto it, not the other way round.
  auto end_on_segment = [&](int k, const Seg& seg, int p) {
    if (p == seg.pa || p == seg.pb) return;  // a shared end point is not a split
    Vec2 foot;
    if (distance_to_segment(r.pos[p], r.pos[seg.pa], r.pos[seg.pb], foot) > tol) return;
    touched = true;
    // A point already on the segment to rounding stays where it is: moving it
    // by an ulp would only make the next round see a change.
    if (foot_priority(seg.rank) > r.rank[p] && (foot - r.pos[p]).norm() > 1e-3 * tol) {
      r.pos.push_back(foot);
      r.rank.push_back(foot_priority(seg.rank));
      const int f = static_cast<int>(r.pos.size()) - 1;
      splits.push_back({k, f});
      moved.push_back({p, f});
    } else {
      splits.push_back({k, p});
    }
  };
  end_on_segment(i, si, sj.pa);
  end_on_segment(i, si, sj.pb);
  end_on_segment(j, sj, si.pa);
  end_on_segment(j, sj, si.pb);
  if (touched) return;

  // Proper crossing: each segment's end points strictly on both sides of the other.
  const Vec2 &a = r.pos[si.pa], &b = r.pos[si.pb], &c = r.pos[sj.pa], &d = r.pos[sj.pb];
  const double s1 = cross(b - a, c - a), s2 = cross(b - a, d - a);
  const double s3 = cross(d - c, a - c), s4 = cross(d - c, b - c);
  if (!((s1 > 0 && s2 < 0) || (s1 < 0 && s2 > 0))) return;
  if (!((s3 > 0 && s4 < 0) || (s3 < 0 && s4 > 0))) return;
  // Place the point by the higher-ranked segment's own parameter, measured
  // from its nearer end, so it lies on that segment's line to rounding. A
  // horizontal or vertical segment gives its coordinate exactly, so joints on
  // a regular lattice meet at exact lattice points.
  auto along = [](const Vec2& p, const Vec2& q, double t) {
    return t <= 0.5 ? Vec2(p + t * (q - p)) : Vec2(q + (1 - t) * (p - q));
  };
  Vec2 x = si.rank >= sj.rank ? along(a, b, s3 / (s3 - s4)) : along(c, d, s1 / (s1 - s2));
  for (const auto& [p, q] : {std::pair{a, b}, std::pair{c, d}}) {
    if (p.x() == q.x()) x.x() = p.x();
    if (p.y() == q.y()) x.y() = p.y();
  }
  r.pos.push_back(x);
  r.rank.push_back(end_priority(std::max(si.rank, sj.rank)));
  const int p = static_cast<int>(r.pos.size()) - 1;
  splits.push_back({i, p});
  splits.push_back({j, p});
}

// ---- Snapping ---------------------------------------------------------------

// Cell (x, y) → the last representative put in it: open addressing with
// linear probing. Snapping looks up every point's neighbour cells, and a
// flat table keeps those look-ups to about one cache miss each.
class CellTable {
 public:
  explicit CellTable(std::size_t expected) {
    std::size_t cap = 16;
    while (cap < 2 * expected) cap *= 2;
    slots_.resize(cap);
    mask_ = cap - 1;
  }
  // The head of cell (x, y), or -1.
  int find(std::int64_t x, std::int64_t y) const {
    for (std::size_t i = hash(x, y);; i = (i + 1) & mask_) {
      const Slot& s = slots_[i];
      if (s.head < 0) return -1;
      if (s.x == x && s.y == y) return s.head;
    }
  }
  // The head of cell (x, y), created empty (-1) if absent. The table never
  // fills: it holds at most `expected` cells.
  int& head(std::int64_t x, std::int64_t y) {
    for (std::size_t i = hash(x, y);; i = (i + 1) & mask_) {
      Slot& s = slots_[i];
      if (s.head < 0) {
        s.x = x;
        s.y = y;
        return s.head;
      }
      if (s.x == x && s.y == y) return s.head;
    }
  }

 private:
  struct Slot {
    std::int64_t x = 0, y = 0;
    int head = -1;  // -1: free
  };
  std::size_t hash(std::int64_t x, std::int64_t y) const {
    std::uint64_t h =
        static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4Full;
    return static_cast<std::size_t>(h ^ (h >> 29)) & mask_;
  }
  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
};

// Greedy clustering: points in order of falling rank (then index) either join
// the nearest existing representative within tol or become one. A
// representative never moves, and higher-ranked positions win. Then each
// moved end point joins its foot's cluster (the foot may have snapped to a
// corner just beyond tol of the end point). Returns point → vertex; vertices
// are numbered in ascending order of their representative point, so a round
// that changes nothing keeps every index.
std::vector<int> snap_points(const Round& r, double tol, const std::vector<Moved>& moved, std::vector<int>& reps) {
  const int n = static_cast<int>(r.pos.size());
  // Ranks are small: bucket the points by falling rank, in index order.
  const int top = n > 0 ? *std::max_element(r.rank.begin(), r.rank.end()) : 0;
  std::vector<int> order;
  order.reserve(n);
  for (int rank = top; rank >= 0; --rank)
    for (int k = 0; k < n; ++k)
      if (r.rank[k] == rank) order.push_back(k);

  // Cells of twice the tolerance: every point within tol of p lies in p's
  // cell or in the neighbours on the side of the cell p is nearer to.
  const double cell = 2 * tol;
  CellTable table(static_cast<std::size_t>(n));
  std::vector<int> next_in_cell(n, -1);
  std::vector<int> rep_of(n, -1);
  for (int p : order) {
    const double fx = r.pos[p].x() / cell, fy = r.pos[p].y() / cell;
    const std::int64_t kx = static_cast<std::int64_t>(std::floor(fx)), ky = static_cast<std::int64_t>(std::floor(fy));
    const std::int64_t sx = fx - static_cast<double>(kx) < 0.5 ? -1 : 1;
    const std::int64_t sy = fy - static_cast<double>(ky) < 0.5 ? -1 : 1;
    int best = -1;
    double best_d = std::numeric_limits<double>::infinity();
    for (const std::int64_t dx : {std::int64_t{0}, sx})
      for (const std::int64_t dy : {std::int64_t{0}, sy})
        for (int q = table.find(kx + dx, ky + dy); q >= 0; q = next_in_cell[q]) {
          const double d = (r.pos[q] - r.pos[p]).norm();
          if (d > tol) continue;
          if (d < best_d || (d == best_d && q < best)) {
            best = q;
            best_d = d;
          }
        }
    if (best >= 0) {
      rep_of[p] = best;
    } else {
      rep_of[p] = p;
      int& head = table.head(kx, ky);
      next_in_cell[p] = head;
      head = p;
    }
  }
  // Union the clusters of moved end points with their feet's; the union's
  // representative is the higher-ranked one (then the lower index).
  std::vector<int> parent(n);
  for (int p = 0; p < n; ++p) parent[p] = p;
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const Moved& m : moved) {
    const int a = find(rep_of[m.end]), b = find(rep_of[m.foot]);
    if (a == b) continue;
    const bool a_wins = r.rank[a] > r.rank[b] || (r.rank[a] == r.rank[b] && a < b);
    if (a_wins)
      parent[b] = a;
    else
      parent[a] = b;
  }
  for (int p = 0; p < n; ++p) rep_of[p] = find(rep_of[p]);

  reps.clear();
  std::vector<int> vertex_of_rep(n, -1);
  for (int p = 0; p < n; ++p)
    if (rep_of[p] == p) {
      vertex_of_rep[p] = static_cast<int>(reps.size());
      reps.push_back(p);
    }
  std::vector<int> vertex(n);
  for (int p = 0; p < n; ++p) vertex[p] = vertex_of_rep[rep_of[p]];
  return vertex;
}

struct SubEdge {
  int lo, hi;  // vertex ids, lo < hi
  int rank, source;
  int from, to;
};

}  // namespace

Arrangement build_arrangement(std::span<const ArrangementSegment> segments, double tol) {
  DDA_ASSERT(tol > 0, "snapping tolerance must be positive");
  Round r;
  r.pos.reserve(2 * segments.size());
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const ArrangementSegment& in = segments[s];
    if ((in.b - in.a).norm() <= tol) continue;  // shorter than the tolerance: a point, not a cut
    const int pa = static_cast<int>(r.pos.size());
    r.pos.push_back(in.a);
    r.pos.push_back(in.b);
    r.rank.push_back(end_priority(in.end_rank));
    r.rank.push_back(end_priority(in.end_rank));
    r.segs.push_back({pa, pa + 1, in.rank, static_cast<int>(s)});
  }

  Arrangement out;
  constexpr int kMaxRounds = 24;       // nearly coincident joints zip together over a few rounds
  std::vector<std::uint64_t> history;  // a hash of each round's vertices and edges
  for (int round = 1;; ++round) {
    const int old_points = static_cast<int>(r.pos.size());

    std::vector<Split> splits;
    std::vector<Moved> moved;
    {
      const SegmentGrid grid(r, tol);
      grid.for_each_candidate_pair([&](int i, int j) {
        intersect_pair(r, i, j, tol, splits, moved);
        if (splits.size() > kMaxSplits)
          throw Error(msg("block cutting: the joints cross more than ", kMaxSplits / 2,
                          " times; check the joint spacings (a model this size cannot be run)"));
      });
    }

    std::vector<int> reps;
    const std::vector<int> vertex = snap_points(r, tol, moved, reps);

    // Split every segment at its vertices, in order along it.
    std::vector<std::size_t> split_start(r.segs.size() + 1, 0);
    for (const Split& sp : splits) ++split_start[sp.seg + 1];
    for (std::size_t k = 1; k < split_start.size(); ++k) split_start[k] += split_start[k - 1];
    std::vector<int> split_points(splits.size());
    {
      std::vector<std::size_t> fill(split_start.begin(), split_start.end() - 1);
      for (const Split& sp : splits) split_points[fill[sp.seg]++] = sp.point;
    }
    std::vector<SubEdge> pieces;
    pieces.reserve(r.segs.size() + splits.size());
    std::vector<std::pair<double, int>> along;  // (parameter, vertex)
    for (std::size_t s = 0; s < r.segs.size(); ++s) {
      const Seg& seg = r.segs[s];
      const Vec2 a = r.pos[seg.pa];
      const Vec2 ab = r.pos[seg.pb] - a;
      const double len2 = ab.squaredNorm();
      along.clear();
      auto add = [&](int point) {
        const int v = vertex[point];
        along.push_back({(r.pos[reps[v]] - a).dot(ab) / len2, v});
      };
      add(seg.pa);
      add(seg.pb);
      for (std::size_t k = split_start[s]; k < split_start[s + 1]; ++k) add(split_points[k]);
      std::sort(along.begin(), along.end());
      along.erase(
          std::unique(along.begin(), along.end(), [](const auto& x, const auto& y) { return x.second == y.second; }),
          along.end());
      for (std::size_t k = 0; k + 1 < along.size(); ++k) {
        const int u = along[k].second, v = along[k + 1].second;
        if (u == v) continue;
        pieces.push_back({std::min(u, v), std::max(u, v), seg.rank, seg.source, u, v});
      }
    }
    // Coincident pieces: the highest rank wins, then the earliest segment.
    std::sort(pieces.begin(), pieces.end(), [](const SubEdge& x, const SubEdge& y) {
      if (x.lo != y.lo) return x.lo < y.lo;
      if (x.hi != y.hi) return x.hi < y.hi;
      if (x.rank != y.rank) return x.rank > y.rank;
      return x.source < y.source;
    });
    pieces.erase(std::unique(pieces.begin(), pieces.end(),
                             [](const SubEdge& x, const SubEdge& y) { return x.lo == y.lo && x.hi == y.hi; }),
                 pieces.end());

    // Settled when the round changed nothing: the vertices are the old points
    // and the edges the old segments (both lists are in the same sorted
    // order). A split that only re-finds an existing edge changes nothing.
    bool same_vertices = round > 1 && static_cast<int>(reps.size()) == old_points;
    for (int p = 0; p < old_points && same_vertices; ++p) same_vertices = reps[p] == p;
    bool settled = same_vertices && pieces.size() == r.segs.size();
    for (std::size_t k = 0; k < pieces.size() && settled; ++k) {
      const Seg& old = r.segs[k];
      settled = pieces[k].lo == std::min(old.pa, old.pb) && pieces[k].hi == std::max(old.pa, old.pb);
    }
    // Or when it went back to an earlier state: among vertices closer than a
    // few tolerances, a crossing a hair from one vertex can snap to its
    // neighbour and an edge swap back and forth between them for ever; any of
    // those states is as good as another at this tolerance.
    std::uint64_t state = 0x9E3779B97F4A7C15ull ^ reps.size();
    for (const SubEdge& e : pieces)
      state = (state ^ (static_cast<std::uint64_t>(e.lo) << 32 | static_cast<std::uint32_t>(e.hi))) * 0x100000001B3ull;
    if (same_vertices && std::find(history.begin(), history.end(), state) != history.end()) settled = true;
    history.push_back(state);

    Round next;
    next.pos.reserve(reps.size());
    next.rank.reserve(reps.size());
    for (int p : reps) {
      next.pos.push_back(r.pos[p]);
      next.rank.push_back(r.rank[p]);
    }
    next.segs.reserve(pieces.size());
    for (const SubEdge& e : pieces) next.segs.push_back({e.from, e.to, e.rank, e.source});
    r = std::move(next);

    if (settled) {
      out.rounds = round;
      break;
    }
    if (round == kMaxRounds)
      throw Error(msg("block cutting: the joint arrangement did not settle after ", kMaxRounds,
                      " snapping rounds (snap tolerance ", tol,
                      "); joints nearly touching at many places may need a larger snap_tolerance"));
  }

  out.vertices = std::move(r.pos);
  out.edges.reserve(r.segs.size());
  for (const Seg& s : r.segs) out.edges.push_back({s.pa, s.pb, s.source});
  return out;
}

}  // namespace dda::geometry
