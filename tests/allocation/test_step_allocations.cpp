// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// A step that neither searches for contacts nor cuts Δt allocates no memory:
// its buffers (contact iteration states, the system, the PCG's vectors and
// patches, the partial sums) are sized once and reused. A step allocating on
// the heap does not fail, it only gets slower; this suite counts the calls
// instead.
//
// Counting: this executable replaces glibc's malloc family with versions that
// count and forward to glibc's own (__libc_malloc ...), so that operator new,
// Eigen's aligned buffers and TBB's task pools are all seen. Only the
// counter's differences over a step are read.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>

#include "../scenes.hpp"
#include "world/world.hpp"

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
}

namespace {
std::atomic<long> g_allocations{0};
}

extern "C" {
void* malloc(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(n);
}
void* calloc(std::size_t count, std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(count, n);
}
void* realloc(void* p, std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(p, n);
}
void* memalign(std::size_t alignment, std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_memalign(alignment, n);
}
void* aligned_alloc(std::size_t alignment, std::size_t n) { return memalign(alignment, n); }
int posix_memalign(void** out, std::size_t alignment, std::size_t n) {
  void* p = memalign(alignment, n);
  if (!p) return 12;  // ENOMEM
  *out = p;
  return 0;
}
}

namespace dda {
namespace {

struct StepCount {
  int steps = 0;         // steps counted (no contact search, no cut)
  long allocations = 0;  // heap allocations in those steps
  int searched_or_cut = 0;
};

// Steps `warmup` steps, then `steps` more, counting the allocations of those
// that neither searched for contacts nor cut Δt.
StepCount allocations_in_steady_steps(World& w, int warmup, int steps) {
  for (int s = 0; s < warmup; ++s) w.step();
  StepCount count;
  for (int s = 0; s < steps; ++s) {
    const long before = g_allocations.load();
    const StepStats stats = w.step();
    const long during = g_allocations.load() - before;
    if (stats.contacts_searched || stats.step_cuts > 0) {
      ++count.searched_or_cut;
      continue;
    }
    ++count.steps;
    count.allocations += during;
  }
  return count;
}

TEST(StepAllocations, CounterSeesAllocations) {
  // The counter itself: a vector's buffer is one allocation.
  const long before = g_allocations.load();
  std::vector<double>* v = new std::vector<double>(1000);
  const long after = g_allocations.load();
  delete v;
  EXPECT_GE(after - before, 2);
}

TEST(StepAllocations, WaveStepsAllocateNothing) {
  // 1 m blocks: re-solves run on patches (PcgSolver::patch_hops), the
  // prediction runs; two threads.
  for (const double size : {1.0, 0.2}) {
    World w = test::kicked_bar(30, 3, size);
    w.controls().threads = 2;
    const StepCount count = allocations_in_steady_steps(w, 10, 40);
    EXPECT_GE(count.steps, 30) << "block size " << size;
    EXPECT_EQ(count.allocations, 0) << "block size " << size << ": over " << count.steps << " steps";
  }
}

TEST(StepAllocations, QuasiStaticWallStepsAllocateNothing) {
  // Long solves: loose open-close solves, stored products; 33 blocks keep
  // block-Jacobi (no multigrid set-up).
  World w = test::brick_wall(4);
  w.controls().threads = 2;
  const StepCount count = allocations_in_steady_steps(w, 10, 40);
  EXPECT_GE(count.steps, 10) << count.searched_or_cut << " of 40 steps searched or cut";
  EXPECT_EQ(count.allocations, 0) << "over " << count.steps << " steps (" << count.searched_or_cut
                                  << " searched or cut, not counted)";
}

}  // namespace
}  // namespace dda
