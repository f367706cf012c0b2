// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The C++ scenes, shared by the tests (engine, geometry, allocation) and the
// C++ benchmarks (bench/). Lua scripts share scripts/bench/scenes.lua, which
// is canonical where both define a scene: brick_wall(n) here is its wall(n),
// and LuaApi.BrickWallIsTheSameSceneInLuaAndCpp holds the two equal.
#include <cmath>
#include <vector>

#include "contact/penalty_contacts.hpp"
#include "world/world.hpp"

namespace dda::test {

// The friction lag's memory of contact i after the last step (the penalty
// laws' per-contact history: contact/friction_lag.hpp).
inline const FrictionMemory& friction_memory(const World& w, std::size_t i) {
  return dynamic_cast<const PenaltyContacts&>(*w.contact_model()).friction_memory()[i];
}

// The rectangle with lower-left corner (x0, y0), width w and height h,
// counter-clockwise.
inline std::vector<Vec2> rectangle(double x0, double y0, double w, double h) {
  return {{x0, y0}, {x0 + w, y0}, {x0 + w, y0 + h}, {x0, y0 + h}};
}

// Rectangle with lower-left corner at `origin` (before rotation), rotated by
// `angle` radians about the global origin.
inline std::vector<Vec2> rotated(const std::vector<Vec2>& pts, double angle) {
  std::vector<Vec2> out;
  const double c = std::cos(angle), s = std::sin(angle);
  for (const Vec2& p : pts) out.emplace_back(c * p.x() - s * p.y(), s * p.x() + c * p.y());
  return out;
}

inline RockMaterial granite() { return RockMaterial{2600, 5e9, 0.25}; }

// A base block held by three fixed points along its length.
inline BlockId add_fixed_base(World& w, const std::vector<Vec2>& outline, int rock) {
  const BlockId b = w.add_block(outline, rock);
  const auto v = w.block_vertices(b);
  w.add_fixed_point(b, v[0] * 0.75 + v[1] * 0.25);
  w.add_fixed_point(b, v[0] * 0.5 + v[1] * 0.5);
  w.add_fixed_point(b, v[0] * 0.25 + v[1] * 0.75);
  return b;
}

// A 1 m × 0.5 m granite block resting on a fixed base inclined at `angle`
// radians, friction `phi` degrees, no cohesion or tension; gravity, Δt =
// 1e-3 s. Returns the block.
inline BlockId block_on_incline(World& w, double angle, double phi) {
  const int rock = w.add_rock_material(granite());
  w.joint_material(0) = JointMaterial{phi, 0, 0};
  add_fixed_base(w, rotated(rectangle(-10, -1, 20, 1), angle), rock);
  const BlockId b = w.add_block(rotated(rectangle(2, 0, 1, 0.5), angle), rock);
  w.controls().gravity = Vec2(0, -9.81);
  w.controls().g1 = 1e-3;
  return b;
}

// wall(N) of scripts/bench/scenes.lua: N columns of 1 m × 0.5 m
// bricks, 2N rows in running bond (half bricks at alternate row ends), on a
// 1 m base held by three fixed points; quasi-static (Shi's static analysis,
// gg = 0: velocities reset every step; Δt = 1e-3 s, g2 = 0.001, g0 = 50E),
// friction 30°, no cohesion or tension, gravity.
inline World brick_wall(int n) {
  World w;
  const RockMaterial rock = granite();
  const int m = w.add_rock_material(rock);
  w.joint_material(0) = JointMaterial{30, 0, 0};
  const BlockId base = w.add_block(rectangle(-1, -1, n + 2, 1), m);
  w.add_fixed_point(base, Vec2(0, -0.5));
  w.add_fixed_point(base, Vec2(n / 2.0, -0.5));
  w.add_fixed_point(base, Vec2(n, -0.5));
  for (int row = 0; row < 2 * n; ++row) {
    const double y = row * 0.5;
    if (row % 2 == 0) {
      for (int c = 0; c < n; ++c) w.add_block(rectangle(c, y, 1, 0.5), m);
    } else {
      w.add_block(rectangle(0, y, 0.5, 0.5), m);
      for (int c = 0; c < n - 1; ++c) w.add_block(rectangle(0.5 + c, y, 1, 0.5), m);
      w.add_block(rectangle(n - 0.5, y, 0.5, 0.5), m);
    }
  }
  Controls& c = w.controls();
  c.gravity = Vec2(0, -9.81);
  c.g1 = 1e-3;
  c.g2 = 0.001;
  c.g0 = 50 * rock.youngs;
  c.open_close_limit = 8;
  c.gg = 0;
  return w;
}

// A bar of columns × rows square blocks of `size` m (block c·rows + r at
// column c, row r), its first column kicked to 1 m/s along x: a stress wave
// (steps of 2e-6 s; joints c = σt = 8 MPa, φ = 40°; g0 = 20E). With 0.2 m
// blocks the contact springs are 25 times the blocks' inertia (2m/Δt²); with
// 1 m blocks a thousandth of it, as in the paper's blast (a local change
// then stays local).
inline World kicked_bar(int columns, int rows, double size = 0.2) {
  World w;
  const int rock = w.add_rock_material(RockMaterial{2000, 50e9, 0.25});
  w.joint_material(0) = JointMaterial{40, 8e6, 8e6};
  for (int c = 0; c < columns; ++c)
    for (int r = 0; r < rows; ++r) w.add_block(test::rectangle(c * size, r * size, size, size), rock);
  Vec6 kick = Vec6::Zero();
  kick[0] = 1.0;
  for (BlockId b = 0; b < rows; ++b) w.set_block_velocity(b, kick);
  w.controls().g0 = 20 * 50e9;
  w.controls().g1 = 2e-6;
  return w;
}

// A block held at every vertex.
inline BlockId add_fixed_block(World& w, const std::vector<Vec2>& outline, int rock) {
  const BlockId b = w.add_block(outline, rock);
  const std::vector<Vec2> corners(w.block_vertices(b).begin(), w.block_vertices(b).end());
  for (const Vec2& v : corners) w.add_fixed_point(b, v);
  return b;
}

// Aligned corners that slide apart (docs/contact_transfer.md): two blocks end to end
// along a horizontal joint, a fixed base on the left (top at y = 0) and a free
// 2 m × 1 m block B on the right (block 2, on a fixed foundation, 1 µm above
// it), their tops on one line. Block A (block 3) on the base, its bottom edge
// meeting B's top edge end to end at x = 0 and its top overhanging to the
// right (its weight's line passes the base's corner after 0.22 m), is pushed
// right at 1 m/s, without friction, over B. Granite, g0 = 50 E, Δt = 1 ms,
// g2 = 0.01, the search range fixed at 0.6 m (a vertex moves 0.3 m before the
// list is searched again for that alone, as in a model of large blocks).
inline World block_sliding_past_aligned_corner(ContactLaw law) {
  World w;
  const int rock = w.add_rock_material(granite());
  w.joint_material(0) = JointMaterial{0, 0, 0};
  add_fixed_block(w, rectangle(-3, -1, 3, 1), rock);  // the base
  add_fixed_block(w, rectangle(0, -2, 3, 1), rock);   // B's foundation
  w.add_block(rectangle(0, -1 + 1e-6, 2, 1), rock);   // B: top at y = 1e-6
  const BlockId a = w.add_block({{-1, 2e-6}, {0, 2e-6}, {1, 1}, {-1, 1}}, rock);
  Controls& c = w.controls();
  c.gravity = Vec2(0, -9.81);
  c.g1 = 1e-3;
  c.g2 = 0.01;
  c.g0 = 50 * granite().youngs;
  c.contact_law = law;
  c.contact_range = 0.6;
  Vec6 push = Vec6::Zero();
  push[0] = 1.0;
  w.set_block_velocity(a, push);
  return w;
}

}  // namespace dda::test
