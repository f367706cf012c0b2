// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Block cutting benchmark: prints the time to cut a few domains into blocks.
//
//   ./build/bench/bench_cutting [repeats]
//
// Cases: the paper's rock bar (Model 1), its Section 4 blasting model, the
// 100 m × 100 m domain with two persistent sets at 0.5 m (about 40,000
// blocks; axis-aligned and at 45°/135°), and a non-persistent, randomly
// varied joint network. Figures only; nothing is asserted.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "geometry/cutting.hpp"
#include "scenes.hpp"  // tests/: test::rectangle

using dda::Vec2;
using namespace dda::geometry;

namespace {

using dda::test::rectangle;  // (x0, y0, width, height)

JointSet persistent_set(double dip, double spacing, Vec2 origin = Vec2::Zero()) {
  JointSet s;
  s.dip_deg = dip;
  s.spacing = spacing;
  s.origin = origin;
  return s;
}

struct Case {
  std::string name;
  CutInput input;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  {
    Case c{"rock bar Model 1 (20 m x 1 m, 0/90 deg at 0.2 m)", {}};
    c.input.domain = rectangle(0, 0, 20, 1);
    c.input.sets = {persistent_set(0, 0.2), persistent_set(90, 0.2)};
    out.push_back(c);
  }
  {
    Case c{"rock bar Model 3 (20 m x 1 m, 0/30 deg at 0.2 m)", {}};
    c.input.domain = rectangle(0, 0, 20, 1);
    c.input.sets = {persistent_set(0, 0.2), persistent_set(30, 0.2)};
    out.push_back(c);
  }
  {
    Case c{"Section 4 (100 m, 45/135 deg at 2 m, 8 m x 4 m chamber)", {}};
    c.input.domain = rectangle(0, 0, 100, 100);
    c.input.holes = {rectangle(46, 48, 8, 4)};
    c.input.sets = {persistent_set(45, 2, Vec2(50, 50)), persistent_set(135, 2, Vec2(50, 50))};
    out.push_back(c);
  }
  {
    Case c{"100 m x 100 m, 0/90 deg at 0.5 m", {}};
    c.input.domain = rectangle(0, 0, 100, 100);
    c.input.sets = {persistent_set(0, 0.5), persistent_set(90, 0.5)};
    out.push_back(c);
  }
  {
    Case c{"100 m x 100 m, 45/135 deg at 0.5 m", {}};
    c.input.domain = rectangle(0, 0, 100, 100);
    c.input.sets = {persistent_set(45, 0.5, Vec2(50, 50)), persistent_set(135, 0.5, Vec2(50, 50))};
    out.push_back(c);
  }
  {
    Case c{"100 m x 100 m, 20/110 deg at 0.5 m + chamber", {}};
    c.input.domain = rectangle(0, 0, 100, 100);
    c.input.holes = {rectangle(46, 48, 8, 4)};
    c.input.sets = {persistent_set(20, 0.5, Vec2(0.123, 0.456)), persistent_set(110, 0.5, Vec2(0.123, 0.456))};
    out.push_back(c);
  }
  {
    Case c{"50 m x 50 m, non-persistent 30/120 deg at 0.5 m, trace 3 m bridge 0.5 m, varied", {}};
    c.input.domain = rectangle(0, 0, 50, 50);
    JointSet a = persistent_set(30, 0.5), b = persistent_set(120, 0.5);
    for (JointSet* s : {&a, &b}) {
      s->trace_length = 3;
      s->bridge_length = 0.5;
      s->spacing_sd = 0.05;
      s->dip_sd_deg = 3;
      s->trace_sd = 0.5;
      s->seed = 7;
    }
    c.input.sets = {a, b};
    c.input.min_block_area = 1e-3;
    out.push_back(c);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  std::printf("%-78s %8s %9s %9s %9s %7s %6s\n", "case", "blocks", "segments", "edges", "dangling", "slivers", "ms");
  for (const Case& c : cases()) {
    double best_ms = 1e300;
    BlockSet result;
    for (int r = 0; r < repeats; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      result = cut_blocks(c.input);
      const auto t1 = std::chrono::steady_clock::now();
      best_ms = std::min(best_ms, std::chrono::duration<double, std::milli>(t1 - t0).count());
    }
    std::printf("%-78s %8zu %9d %9d %9d %7d %6.1f\n", c.name.c_str(), result.blocks.size(), result.stats.input_segments,
                result.stats.edges, result.stats.dangling_edges_removed, result.stats.slivers_merged, best_ms);
  }
  std::printf("(best of %d runs; one thread)\n", repeats);
  return 0;
}
