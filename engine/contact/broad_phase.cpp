// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "contact/broad_phase.hpp"

#include <algorithm>
#include <cmath>

#include "core/parallel.hpp"

namespace dda {

namespace {
struct Box {
  Vec2 lo, hi;
};
bool overlap(const Box& a, const Box& b) {
  return a.lo.x() <= b.hi.x() && b.lo.x() <= a.hi.x() && a.lo.y() <= b.hi.y() && b.lo.y() <= a.hi.y();
}
}  // namespace

std::vector<std::pair<int, int>> find_candidate_pairs(const BlockPolygons& blocks, double range) {
  const int n = blocks.count();
  std::vector<std::pair<int, int>> pairs;
  if (n < 2) return pairs;

  // Boxes grown by half the range on every side: overlapping boxes are
  // within `range` of each other.
  std::vector<Box> box(n);
  std::vector<double> extent(n);
  parallel_for_each(n, [&](std::size_t b) {
    Box bx{Vec2::Constant(INFINITY), Vec2::Constant(-INFINITY)};
    for (const Vec2& v : blocks.of(static_cast<int>(b))) {
      bx.lo = bx.lo.cwiseMin(v);
      bx.hi = bx.hi.cwiseMax(v);
    }
    bx.lo.array() -= 0.5 * range;
    bx.hi.array() += 0.5 * range;
    box[b] = bx;
    extent[b] = (bx.hi - bx.lo).maxCoeff();
  });

  // Cell size: a few times the median extent. Blocks larger than a cell are
  // "large" and tested against every block (a base block, a long beam).
  std::vector<double> sorted_extent = extent;
  std::nth_element(sorted_extent.begin(), sorted_extent.begin() + n / 2, sorted_extent.end());
  const double cell = 2.0 * sorted_extent[n / 2];
  Vec2 lo = Vec2::Constant(INFINITY), hi = Vec2::Constant(-INFINITY);
  for (const Box& b : box) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  // Keep the grid no larger than ~4 cells per block (blocks scattered far
  // apart). Cell counts are worked out in floating point and cast only once
  // they are small: blocks 1e200 cells apart must not overflow a long. A model
  // whose span overflows (a diverging one) gets no grid: every block is
  // "large".
  const double span = (hi - lo).maxCoeff();
  const bool gridded = std::isfinite(span) && std::isfinite(cell) && cell > 0;
  double cs = gridded ? cell : INFINITY;
  auto cells_along = [&](double length) { return std::max(1.0, std::ceil(length / cs)); };
  while (gridded && cells_along(span) * cells_along(span) > 4.0 * n + 1024) cs *= 2;
  const long nx = gridded ? static_cast<long>(std::ceil((hi.x() - lo.x()) / cs)) + 1 : 1;
  const long ny = gridded ? static_cast<long>(std::ceil((hi.y() - lo.y()) / cs)) + 1 : 1;

  std::vector<int> large, ordinary;
  for (int b = 0; b < n; ++b) (!gridded || extent[b] > cs ? large : ordinary).push_back(b);

  // Bucket ordinary blocks by the cell of their lower-left corner (counting sort).
  auto cell_of = [&](const Vec2& p) {
    const long cx = std::clamp(static_cast<long>((p.x() - lo.x()) / cs), 0L, nx - 1);
    const long cy = std::clamp(static_cast<long>((p.y() - lo.y()) / cs), 0L, ny - 1);
    return std::pair<long, long>(cx, cy);
  };
  std::vector<int> cell_start(nx * ny + 1, 0), cell_items(ordinary.size());
  for (int b : ordinary) {
    const auto [cx, cy] = cell_of(box[b].lo);
    ++cell_start[cy * nx + cx + 1];
  }
  for (long c = 0; c < nx * ny; ++c) cell_start[c + 1] += cell_start[c];
  {
    std::vector<int> fill(cell_start.begin(), cell_start.end() - 1);
    for (int b : ordinary) {  // ascending b: each cell's list is sorted
      const auto [cx, cy] = cell_of(box[b].lo);
      cell_items[fill[cy * nx + cx]++] = b;
    }
  }

  // Each ordinary block collects partners j > i from the 3×3 cells around it
  // (boxes no larger than a cell overlap only if their corners are within one
  // cell), and from the large blocks. Per-chunk lists, joined in order.
  const std::size_t chunks = chunk_count(n);
  std::vector<std::vector<std::pair<int, int>>> found(chunks);
  std::vector<char> is_large(n, 0);
  for (int b : large) is_large[b] = 1;
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    auto& out = found[c];
    std::vector<int> partners;
    const int end = static_cast<int>(std::min<std::size_t>(n, (c + 1) * kChunk));
    for (int i = static_cast<int>(c * kChunk); i < end; ++i) {
      partners.clear();
      if (is_large[i]) {
        for (int j = i + 1; j < n; ++j)
          if (overlap(box[i], box[j])) partners.push_back(j);
      } else {
        const auto [cx, cy] = cell_of(box[i].lo);
        for (long y = std::max(0L, cy - 1); y <= std::min(ny - 1, cy + 1); ++y)
          for (long x = std::max(0L, cx - 1); x <= std::min(nx - 1, cx + 1); ++x)
            for (int k = cell_start[y * nx + x]; k < cell_start[y * nx + x + 1]; ++k) {
              const int j = cell_items[k];
              if (j > i && overlap(box[i], box[j])) partners.push_back(j);
            }
        for (int j : large)
          if (j > i && overlap(box[i], box[j])) partners.push_back(j);
      }
      std::sort(partners.begin(), partners.end());
      for (int j : partners) out.emplace_back(i, j);
    }
  });
  std::size_t total = 0;
  for (const auto& f : found) total += f.size();
  pairs.reserve(total);
  for (const auto& f : found) pairs.insert(pairs.end(), f.begin(), f.end());
  return pairs;
}

}  // namespace dda
