// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The wave model (world/wave_model.hpp): the loads' highest frequency, the
// element size the engine picks from it, the blocks meshed in place before
// the first step with every load, boundary and followed point following
// them, and the warnings on choices by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "../scenes.hpp"
#include "core/error.hpp"
#include "loading/load_frequency.hpp"
#include "world/checkpoint.hpp"
#include "world/wave_model.hpp"

using namespace dda;

namespace {

std::vector<std::pair<double, double>> sine_pulse(double f, double periods, double a = 5e6, int n = 400) {
  std::vector<std::pair<double, double>> s;
  for (int i = 0; i <= n; ++i) {
    const double t = periods / f * i / n;
    s.emplace_back(t, a * std::sin(2 * kPi * f * t));
  }
  return s;
}

// The edges of every block with both ends on the line x = x0 (the ends of a
// bar whose blocks were meshed when added).
std::vector<EdgeRef> edges_on_x(const World& w, double x0) {
  std::vector<EdgeRef> edges;
  for (BlockId b = 0; b < static_cast<BlockId>(w.block_count()); ++b) {
    const auto v = w.block_vertices(b);
    for (std::size_t k = 0; k < v.size(); ++k)
      if (std::abs(v[k].x() - x0) < 1e-9 && std::abs(v[(k + 1) % v.size()].x() - x0) < 1e-9)
        edges.push_back({b, static_cast<int>(k)});
  }
  return edges;
}

// A 4 m × 1 m bar of 1 m square blocks (ν = 0.25, plane stress: C_S =
// sqrt(G/ρ) = 3162 m/s), a pressure history on its left end, its right end
// fixed, a followed point in the middle.
struct Bar {
  World w;
  int load, tracked;
  explicit Bar(const History& pressure, double mesh_size = -1) {
    w.controls().mesh_size = mesh_size;
    w.controls().g1 = 1e-5;
    const int rock = w.add_rock_material(RockMaterial{2000, 50e9, 0.25});
    for (int i = 0; i < 4; ++i) w.add_block(test::rectangle(i, 0, 1, 1), rock);
    load = w.add_pressure_load(mesh_size > 0 ? edges_on_x(w, 0) : std::vector<EdgeRef>{EdgeRef{0, 3}});
    w.set_pressure_history(load, pressure);
    w.fix_edges(mesh_size > 0 ? edges_on_x(w, 4) : std::vector<EdgeRef>{EdgeRef{3, 1}});
    tracked = mesh_size > 0 ? -1 : w.add_tracked_point(2, Vec2(2.3, 0.6));  // (the unmeshed bars)
  }
};

double pressure_force_x(const World& w, int load) {
  double length = 0;
  for (const EdgeRef& e : w.pressure_edges(load)) {
    const auto v = w.block_vertices(e.block);
    length += (v[(e.edge + 1) % v.size()] - v[e.edge]).norm();
  }
  return length;
}

}  // namespace

TEST(WaveModel, ASinePulsesHighestFrequencyHoldsNinetyNinePercentOfItsEnergy) {
  // Reference: the energy spectrum of A·sin(2πf₀t) over one period or half
  // of one, integrated exactly (a midpoint rule over 1 Hz up to 100 f₀ does
  // it to 1e-4): 99 % lies below 2.20 f₀ (one period) and 2.365 f₀ (half).
  for (const auto& [periods, expected] : {std::pair{1.0, 2.20}, std::pair{0.5, 2.365}}) {
    const LoadSignal s{sine_pulse(1000, periods, 5e6, 2000), SignalKind::Force, "sine"};
    EXPECT_NEAR(signal_frequency(s) / 1000, expected, 0.01) << periods;
  }
  // One short interval (a sample 1 ns after the pulse's end) raises the
  // rate the samples could carry to 500 MHz but not the pulse's frequency.
  std::vector<std::pair<double, double>> closed = sine_pulse(1000, 1.0, 5e6, 100);
  closed.emplace_back(closed.back().first + 1e-9, 0.0);
  EXPECT_NEAR(signal_frequency({closed, SignalKind::Force, "closed sine"}) / 1000, 2.20, 0.01);
  // A constant, and a load switched on and held, are static.
  EXPECT_EQ(signal_frequency({{{0, 3}, {1, 3}}, SignalKind::Force, "constant"}), 0);
  EXPECT_EQ(signal_frequency({{{0, 0}, {1e-9, 3}, {1, 3}}, SignalKind::Force, "step"}), 0);
  // A prescribed displacement is read as its velocity: a displacement that
  // follows the integral of a half sine has the half sine's frequency.
  std::vector<std::pair<double, double>> u;
  for (const auto& [t, v] : sine_pulse(1000, 0.5, 1, 2000))
    u.emplace_back(t, (1 - std::cos(2 * kPi * 1000 * t)) / (2 * kPi * 1000));
  EXPECT_NEAR(signal_frequency({u, SignalKind::Displacement, "u"}) / 1000, 2.365, 0.02);
}

TEST(WaveModel, APulseMeshesBlocksLargerThanItsElementAndLoadsFollow) {
  // Half a sine period at 1 kHz: 99 % of its energy below 2365 Hz, elements
  // of C_S/(12·2365) = 0.111 m, so each 1 m block is meshed (9 × 9 cells of
  // four triangles: 324 elements), ids kept.
  Bar bar(History(sine_pulse(1000, 0.5)));
  const WaveModel& wave = bar.w.decide_wave_model();
  EXPECT_TRUE(wave.active);
  EXPECT_EQ(wave.meshed_blocks, 4);
  EXPECT_NEAR(wave.frequency, 2365, 15);
  EXPECT_NEAR(wave.element_size, std::sqrt(20e9 / 2000) / (12 * wave.frequency), 1e-12);
  EXPECT_EQ(bar.w.block_count(), 4u * 324u);
  EXPECT_EQ(bar.w.mesh_generation(), 1);
  for (BlockId b = 0; b < 4; ++b) EXPECT_EQ(bar.w.block_material(b), 0);
  // The pressure stands on the element edges along x = 0, 1 m of them.
  EXPECT_EQ(bar.w.pressure_edges(bar.load).size(), 9u);
  EXPECT_NEAR(pressure_force_x(bar.w, bar.load), 1.0, 1e-12);
  for (const EdgeRef& e : bar.w.pressure_edges(bar.load))
    for (const Vec2& v : {bar.w.block_vertices(e.block)[e.edge]}) EXPECT_NEAR(v.x(), 0, 1e-12);
  // The old edge maps onto the same element edges.
  EXPECT_EQ(bar.w.edges_since_meshing(EdgeRef{0, 3}), bar.w.pressure_edges(bar.load));
  // The followed point is on the element under it.
  const BlockId under = bar.w.tracked_block(bar.tracked);
  bool inside = false;
  const auto v = bar.w.block_vertices(under);
  double area = 0;  // the point splits the triangle into three of its area
  for (std::size_t k = 0; k < 3; ++k)
    area += std::abs((v[k] - Vec2(2.3, 0.6)).x() * (v[(k + 1) % 3] - Vec2(2.3, 0.6)).y() -
                     (v[k] - Vec2(2.3, 0.6)).y() * (v[(k + 1) % 3] - Vec2(2.3, 0.6)).x()) /
            2;
  inside = std::abs(area - bar.w.block_area(under)) < 1e-12;
  EXPECT_TRUE(inside);
  // The scheme: lumped mass and Newmark where the controls say "auto".
  EXPECT_EQ(bar.w.integrator_in_use(), Integrator::Newmark);
  EXPECT_EQ(bar.w.mesh_mass_in_use(), MeshMass::Lumped);
}

TEST(WaveModel, TheFixedEndHoldsEveryNodeAfterMeshing) {
  // Fixed edges are made again on the element edges: the right end's ten
  // nodes (9 segments) are held, and the bar, pushed, does not move there.
  Bar bar(History(sine_pulse(1000, 0.5)));
  bar.w.decide_wave_model();
  for (int i = 0; i < 40; ++i) bar.w.step();
  const auto edges = bar.w.edges_since_meshing(EdgeRef{3, 1});
  ASSERT_EQ(edges.size(), 9u);
  for (const EdgeRef& e : edges) {
    const Vec2 p = bar.w.block_vertices(e.block)[e.edge], p0 = bar.w.block_initial_vertices(e.block)[e.edge];
    EXPECT_LT((p - p0).norm(), 1e-9) << p0.transpose();
  }
}

namespace {

// The bar as it was built: four first-order blocks, stepped with Shi's scheme.
void expect_first_order_under_shi(const Bar& bar, const WaveModel& wave) {
  EXPECT_FALSE(wave.active);
  EXPECT_EQ(wave.meshed_blocks, 0);
  EXPECT_EQ(bar.w.block_count(), 4u);
  EXPECT_EQ(bar.w.integrator_in_use(), Integrator::Shi);
}

}  // namespace

TEST(WaveModel, AModelWithinAWavelengthKeepsItsFirstOrderBlocks) {
  // A slow pulse (half a sine at 20 Hz: elements of 5.6 m, a shear
  // wavelength of 67 m) leaves the 4 m bar's 1 m blocks as they are, and
  // Shi's scheme: the bar moves as a body.
  Bar bar(History(sine_pulse(20, 0.5)));
  const WaveModel& wave = bar.w.decide_wave_model();
  expect_first_order_under_shi(bar, wave);
  EXPECT_TRUE(wave.warnings.empty());
}

TEST(WaveModel, BlocksWithinTheElementSizeAreMeshedWhereTheModelSpansAWavelength) {
  // Half a sine at 800 Hz: 99 % of its energy below 1892 Hz, elements of
  // 0.139 m, a shear wavelength of 1.67 m. A bar of forty 0.1 m blocks
  // (4 m) spans it: each block, within the element size, is meshed into
  // the four elements of its outline, under lumped mass and Newmark.
  World w;
  w.controls().g1 = 2e-6;
  const int rock = w.add_rock_material(RockMaterial{2000, 50e9, 0.25});
  for (int i = 0; i < 40; ++i) w.add_block(test::rectangle(0.1 * i, 0, 0.1, 0.1), rock);
  const int load = w.add_pressure_load({EdgeRef{0, 3}});
  w.set_pressure_history(load, History(sine_pulse(800, 0.5)));
  const WaveModel& wave = w.decide_wave_model();
  EXPECT_TRUE(wave.active);
  EXPECT_EQ(wave.meshed_blocks, 40);
  EXPECT_NEAR(wave.element_size, 0.139, 5e-4);
  EXPECT_EQ(w.block_count(), 40u * 4u);
  EXPECT_EQ(w.integrator_in_use(), Integrator::Newmark);
  EXPECT_EQ(w.mesh_mass_in_use(), MeshMass::Lumped);
}

TEST(WaveModel, AMeshBeyondTheBudgetKeepsFirstOrderBlocksAndSaysSo) {
  // Half a sine at 20 kHz needs elements of C_S/(12·47.3 kHz) = 5.6 mm:
  // about 4 × 2·(1/0.0056)² = 260 000 elements, over the budget of 20 000.
  // The blocks stay first-order under Shi's scheme, and a warning names the
  // size, the count and the controls that mesh them.
  Bar bar(History(sine_pulse(20000, 0.5)));
  const WaveModel& wave = bar.w.decide_wave_model();
  expect_first_order_under_shi(bar, wave);
  ASSERT_EQ(wave.warnings.size(), 1u);
  EXPECT_NE(wave.warnings[0].find("needs elements of 0.006 m"), std::string::npos) << wave.warnings[0];
  EXPECT_NE(wave.warnings[0].find("more than the 20000"), std::string::npos) << wave.warnings[0];
  EXPECT_NE(wave.warnings[0].find("mesh_size = 0.006"), std::string::npos) << wave.warnings[0];
}

TEST(WaveModel, NoDynamicLoadKeepsFirstOrderBlocks) {
  Bar bar(History::constant(1e6));
  const WaveModel& wave = bar.w.decide_wave_model();
  EXPECT_EQ(wave.frequency, 0);
  EXPECT_FALSE(wave.active);
  EXPECT_EQ(bar.w.block_count(), 4u);
}

TEST(WaveModel, AStatedFrequencyIsTheOneUsed) {
  Bar bar(History(sine_pulse(20, 0.5)));
  bar.w.controls().max_frequency = 3000;
  const WaveModel& wave = bar.w.decide_wave_model();
  EXPECT_EQ(wave.frequency, 3000);
  EXPECT_TRUE(wave.active);
}

TEST(WaveModel, ChoicesByHandAreKeptWithAWarningNamingTheFigure) {
  // First-order blocks by hand (mesh_size = 0) under the 1 kHz pulse.
  Bar first_order(History(sine_pulse(1000, 0.5)), 0);
  const WaveModel& a = first_order.w.decide_wave_model();
  EXPECT_FALSE(a.active);
  EXPECT_EQ(first_order.w.block_count(), 4u);
  ASSERT_EQ(a.warnings.size(), 1u);
  EXPECT_NE(a.warnings[0].find("wrong-sign lobe"), std::string::npos);
  EXPECT_NE(a.warnings[0].find("docs/waves.md"), std::string::npos);
  // A mesh by hand coarser than the load needs (0.5 m against 0.111 m).
  Bar coarse(History(sine_pulse(1000, 0.5)), 0.5);
  const WaveModel& b = coarse.w.decide_wave_model();
  EXPECT_TRUE(b.active);  // meshed blocks under a dynamic load: the wave scheme
  ASSERT_EQ(b.warnings.size(), 1u);
  EXPECT_NE(b.warnings[0].find("under-resolves"), std::string::npos);
  EXPECT_NE(b.warnings[0].find("docs/waves.md"), std::string::npos);
}

TEST(WaveModel, ADamagedMeshingMapInACheckpointIsRefused) {
  // Checkpoints are untrusted input (docs/robustness.md): the in-place
  // meshing's map (the old blocks' first edge slots, 0 4 8 12 16 for four
  // squares) is checked against the pieces it indexes before anything is
  // built from it, and an old edge past its block is refused, not read.
  Bar bar(History(sine_pulse(1000, 0.5)));
  bar.w.decide_wave_model();
  bar.w.step();
  std::string payload = checkpoint_bytes(bar.w).substr(kCheckpointHeaderBytes);
  std::string map(8, '\0');
  const std::uint64_t n = 5;
  std::memcpy(map.data(), &n, 8);
  for (const std::int32_t v : {0, 4, 8, 12, 16}) map.append(reinterpret_cast<const char*>(&v), 4);
  const std::size_t at = payload.find(map, payload.find("wave model"));
  ASSERT_NE(at, std::string::npos);
  const std::int32_t past = 17;
  std::memcpy(payload.data() + at + map.size() - 4, &past, 4);
  try {
    checkpoint_from_bytes(checkpoint_file(payload), "checkpoint 'x'");
    ADD_FAILURE() << "a meshing map with 17 slots for 16 edges was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("meshing map"), std::string::npos) << e.what();
  }
  EXPECT_THROW(bar.w.edges_since_meshing(EdgeRef{0, 4}), Error);
  EXPECT_EQ(bar.w.edges_since_meshing(EdgeRef{0, 3}).size(), 9u);
}
