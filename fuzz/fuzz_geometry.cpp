// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// libFuzzer target: the geometry input. The bytes become a domain polygon,
// holes, joint sets, explicit joints, material regions and explicit blocks;
// cut_blocks must either cut them or throw dda::Error, and a World built from
// the result must take its first step or throw dda::Error. Anything else (a
// crash, a sanitizer report, another exception, a hang) is a finding.
//
// Coordinates come mostly from a small integer grid, so that coinciding
// points, collinear edges and touching holes (the hard cases) are frequent;
// some are raw doubles (NaN, infinities, huge and tiny values). The model
// size is bounded (joint spacing at least 1/40 of the domain, at most 200
// blocks stepped): size limits are tested by the memory estimate, not here.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "core/error.hpp"
#include "geometry/cutting.hpp"
#include "world/cut_blocks.hpp"
#include "world/world.hpp"

namespace {

using dda::Vec2;

double coordinate(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange<int>(0, 7)) {
    case 0:
      return in.ConsumeFloatingPoint<double>();  // anything, NaN and infinities included
    case 1:
      return in.ConsumeFloatingPointInRange<double>(-10, 10);
    default:
      return in.ConsumeIntegralInRange<int>(-4, 4) * 0.5;  // the grid
  }
}

Vec2 point(FuzzedDataProvider& in) {
  const double x = coordinate(in);
  return {x, coordinate(in)};
}

std::vector<Vec2> polygon(FuzzedDataProvider& in, int max_vertices) {
  std::vector<Vec2> p(in.ConsumeIntegralInRange<int>(0, max_vertices));
  for (Vec2& v : p) v = point(in);
  return p;
}

void print_polygon(const char* what, const std::vector<Vec2>& p) {
  std::fprintf(stderr, "%s:", what);
  for (const Vec2& v : p) std::fprintf(stderr, " {%.17g, %.17g}", v.x(), v.y());
  std::fprintf(stderr, "\n");
}

void print(const dda::geometry::CutInput& cut, const std::vector<std::vector<Vec2>>& blocks) {
  print_polygon("domain", cut.domain);
  for (const auto& h : cut.holes) print_polygon("hole", h);
  for (const auto& s : cut.sets)
    std::fprintf(
        stderr,
        "set: dip %.17g spacing %.17g origin {%.17g, %.17g} material %d trace %.17g bridge %.17g sd %.17g %.17g "
        "%.17g seed %llu\n",
        s.dip_deg, s.spacing, s.origin.x(), s.origin.y(), s.joint_material, s.trace_length, s.bridge_length,
        s.spacing_sd, s.dip_sd_deg, s.trace_sd, static_cast<unsigned long long>(s.seed));
  for (const auto& l : cut.lines)
    std::fprintf(stderr, "line: {%.17g, %.17g} {%.17g, %.17g} material %d\n", l.a.x(), l.a.y(), l.b.x(), l.b.y(),
                 l.joint_material);
  for (const auto& r : cut.regions) print_polygon("region", r.polygon);
  std::fprintf(stderr, "min_block_area %.17g sliver %s snap %.17g inner_cut %d\n", cut.min_block_area,
               cut.sliver_policy == dda::geometry::SliverPolicy::Merge ? "merge" : "error", cut.snap_tolerance,
               cut.inner_cut_material);
  for (const auto& b : blocks) print_polygon("block", b);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  dda::geometry::CutInput cut;
  const bool box = in.ConsumeBool();
  if (box) {
    const double w = in.ConsumeIntegralInRange<int>(1, 8) * 0.5, h = in.ConsumeIntegralInRange<int>(1, 8) * 0.5;
    cut.domain = {{-2, -2}, {-2 + w, -2}, {-2 + w, -2 + h}, {-2, -2 + h}};
  } else {
    cut.domain = polygon(in, 10);
  }
  const int holes = in.ConsumeIntegralInRange<int>(0, 3);
  for (int i = 0; i < holes; ++i) cut.holes.push_back(polygon(in, 6));
  const int sets = in.ConsumeIntegralInRange<int>(0, 3);
  for (int i = 0; i < sets; ++i) {
    dda::geometry::JointSet s;
    s.dip_deg = in.ConsumeBool() ? in.ConsumeIntegralInRange<int>(-4, 8) * 22.5 : in.ConsumeFloatingPoint<double>();
    s.spacing = in.ConsumeIntegralInRange<int>(1, 8) * 0.25;
    if (in.ConsumeBool()) s.spacing = in.ConsumeFloatingPointInRange<double>(0.2, 4);
    s.origin = point(in);
    s.joint_material = in.ConsumeIntegralInRange<int>(0, 1);
    if (in.ConsumeBool()) {
      s.trace_length = in.ConsumeFloatingPointInRange<double>(-1, 4);
      s.bridge_length = in.ConsumeFloatingPointInRange<double>(-1, 4);
    }
    if (in.ConsumeBool()) {
      s.spacing_sd = in.ConsumeFloatingPointInRange<double>(-0.1, 0.5);
      s.dip_sd_deg = in.ConsumeFloatingPointInRange<double>(-5, 30);
      s.trace_sd = in.ConsumeFloatingPointInRange<double>(-0.1, 1);
    }
    s.seed = in.ConsumeIntegral<std::uint64_t>();
    cut.sets.push_back(s);
  }
  const int lines = in.ConsumeIntegralInRange<int>(0, 8);
  for (int i = 0; i < lines; ++i) {
    dda::geometry::JointLine l;
    l.a = point(in);
    l.b = point(in);
    l.joint_material = in.ConsumeIntegralInRange<int>(-1, 1);
    cut.lines.push_back(l);
  }
  const int regions = in.ConsumeIntegralInRange<int>(0, 2);
  for (int i = 0; i < regions; ++i) cut.regions.push_back({polygon(in, 6), in.ConsumeIntegralInRange<int>(-1, 1)});
  cut.min_block_area = in.ConsumeBool() ? in.ConsumeFloatingPointInRange<double>(-0.1, 0.5) : 0;
  cut.sliver_policy = in.ConsumeBool() ? dda::geometry::SliverPolicy::Merge : dda::geometry::SliverPolicy::Error;
  cut.snap_tolerance = in.ConsumeBool() ? in.ConsumeFloatingPointInRange<double>(-1e-3, 1e-2) : 0;
  cut.inner_cut_material = in.ConsumeIntegralInRange<int>(-1, 1);
  std::vector<std::vector<Vec2>> explicit_blocks(in.ConsumeIntegralInRange<int>(0, 3));
  for (auto& b : explicit_blocks) b = polygon(in, 6);

  if (std::getenv("DDA_FUZZ_PRINT")) print(cut, explicit_blocks);  // to turn a finding into a test

  dda::Controls controls;
  controls.threads = 1;
  controls.gravity = {0, -9.81};
  dda::World world(controls);
  try {
    world.add_rock_material({});
    world.add_rock_material({});
    world.add_joint_material({});
    if (!cut.domain.empty()) {
      const dda::geometry::BlockSet set = dda::geometry::cut_blocks(cut);
      if (set.blocks.size() > 200) return 0;
      dda::add_cut_blocks(world, set, {});
    }
    for (auto& b : explicit_blocks) world.add_block(b, 0);
    if (world.block_count() > 0 && world.block_count() <= 200) world.step();
  } catch (const dda::Error&) {
    // refused with a message: the expected outcome for bad input
  }
  return 0;
}
