// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Deterministic parallel building blocks. Results never depend on the thread
// count: work is split into fixed-size chunks and partial results are
// combined serially in chunk order.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <cstddef>
#include <vector>

namespace dda {

// Fixed chunking, independent of the number of threads.
constexpr std::size_t kChunk = 512;

inline std::size_t chunk_count(std::size_t n) { return (n + kChunk - 1) / kChunk; }

// for_each(i) over [0, n) in parallel; f must only write to data owned by i.
template <typename F>
void parallel_for_each(std::size_t n, F&& f, std::size_t grain = 64) {
  if (n == 0) return;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) f(i);
  });
}

// Sum of f(i) over [0, n): partial sums per fixed chunk, combined in order.
template <typename T, typename F>
T deterministic_sum(std::size_t n, F&& f) {
  const std::size_t chunks = chunk_count(n);
  std::vector<T> partial(chunks, T(0));
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
    T s(0);
    const std::size_t end = std::min(n, (c + 1) * kChunk);
    for (std::size_t i = c * kChunk; i < end; ++i) s += f(i);
    partial[c] = s;
  });
  T total(0);
  for (const T& p : partial) total += p;
  return total;
}

// Results that do not depend on the order of their parts (maxima, flags)
// need no fixed chunks: ranges of at least this many items, split as TBB
// pleases (small enough that a pass over a few thousand blocks feeds many
// threads).
constexpr std::size_t kOrderFreeGrain = 128;

// Max of f(i) over [0, n). Max is exact in any order, so partial maxima are
// joined as TBB pleases (no buffer to allocate: this runs several times per
// step).
template <typename T, typename F>
T parallel_max(std::size_t n, T init, F&& f) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, kOrderFreeGrain), init,
      [&](const tbb::blocked_range<std::size_t>& r, T m) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const T v = f(i);
          if (v > m) m = v;
        }
        return m;
      },
      [](T a, T b) { return b > a ? b : a; });
}

// How many i in [0, n) pred(i) holds for: a count is exact in any order (no
// buffer to allocate, unlike deterministic_sum).
template <typename F>
std::size_t parallel_count(std::size_t n, F&& pred) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, kOrderFreeGrain), std::size_t(0),
      [&](const tbb::blocked_range<std::size_t>& r, std::size_t count) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) count += pred(i) ? 1 : 0;
        return count;
      },
      [](std::size_t a, std::size_t b) { return a + b; });
}

// Whether pred(i) holds for every i in [0, n): a flag is exact in any order
// (a range stops at its first failure).
template <typename F>
bool parallel_all(std::size_t n, F&& pred) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, kOrderFreeGrain), true,
      [&](const tbb::blocked_range<std::size_t>& r, bool all) {
        for (std::size_t i = r.begin(); all && i != r.end(); ++i) all = pred(i);
        return all;
      },
      [](bool a, bool b) { return a && b; });
}

}  // namespace dda
