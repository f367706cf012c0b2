// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Checkpoints as untrusted input (world/checkpoint.hpp, core/archive.hpp,
// core/load_check.hpp): a payload edited with both checksums recomputed
// (checkpoint_file: anyone can do it) is refused with a message naming the
// damage, before anything is built from it; it never corrupts memory (the
// sanitizer build runs these). Each case is one the audit or the fuzz
// target found: a contact's block id past the blocks (a heap overflow in
// ContactOperator::set_contacts), an outline running past the vertices (an
// out-of-bounds read at the first step), counts that made the loader
// allocate far more than the file holds, flags other than 0 and 1, enums
// out of range, and terminal escapes echoed from the file.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>

#include "../scenes.hpp"
#include "core/error.hpp"
#include "world/checkpoint.hpp"

namespace dda {
namespace {

// A small blast (6 × 2 blocks, cohesive joints, a pressure on the left
// edges, viscous boundaries on the right, fixed points, gravity), three
// steps in: contacts, loads and boundaries all hold state.
World stepped_model() {
  World w;
  const int rock = w.add_rock_material(RockMaterial{2600, 30e9, 0.25});
  w.joint_material(0) = JointMaterial{35, 0.5e6, 0.2e6};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 2; ++r) w.add_block(test::rectangle(c, r, 1, 1), rock);
  const int p = w.add_pressure_load({{0, 3}, {1, 3}}, 0);
  w.set_pressure_history(p, History({{0, 0}, {1e-4, 5e6}, {2e-4, 0}}));
  w.add_viscous_boundary({{6, 1}, {7, 1}});
  w.add_fixed_point(0, Vec2(0.5, 0.05));
  w.add_displacement_target(2, Vec2(1.5, 0.05), Vec2(1, 0));
  w.set_target_acceleration_history(0, History({{0, 0}, {1e-3, 1}}));
  w.controls().gravity = Vec2(0, -9.81);
  w.controls().g0 = 20 * 30e9;
  w.controls().g1 = 1e-5;
  w.controls().mesh_size = 0;  // first-order blocks: the indices below are theirs
  for (int i = 0; i < 3; ++i) w.step();
  return w;
}

std::string payload_of(const World& w) { return checkpoint_bytes(w).substr(kCheckpointHeaderBytes); }

// The offset just after the marker of part `name` (its length, then its name).
std::size_t after_part(const std::string& payload, const std::string& name) {
  std::string marker(8, '\0');
  const std::uint64_t n = name.size();
  std::memcpy(marker.data(), &n, 8);
  marker += name;
  const std::size_t at = payload.find(marker);
  EXPECT_NE(at, std::string::npos) << name;
  return at + marker.size();
}

template <class T>
void poke(std::string& payload, std::size_t at, T value) {
  std::memcpy(payload.data() + at, &value, sizeof value);
}

template <class T>
T peek(const std::string& payload, std::size_t at) {
  T value;
  std::memcpy(&value, payload.data() + at, sizeof value);
  return value;
}

// The payload sealed (size and both checksums right) must be refused with
// a message that starts with its name and holds `words`.
void expect_refused(const std::string& payload, const std::string& words) {
  try {
    checkpoint_from_bytes(checkpoint_file(payload), "checkpoint 'x'");
    ADD_FAILURE() << "accepted; expected: " << words;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("checkpoint 'x' ", 0), 0u) << e.what();
  }
}

// Offsets in a Contact's bytes (core/archive.hpp writes its fields in order).
constexpr std::size_t kContactVBlock = 0, kContactState = 20, kContactIntact = 21;

TEST(CheckpointDamage, TheModelLoadsAsSaved) {
  const World w = stepped_model();
  ASSERT_GT(w.contacts().size(), 0u);
  EXPECT_EQ(checkpoint_from_bytes(checkpoint_bytes(w), "x").world.state_hash(), w.state_hash());
}

TEST(CheckpointDamage, AContactOnABlockPastTheModelIsRefused) {
  // The audit's reproduction: the first contact's block id set to 40 (the
  // model has 8), both checksums recomputed. It was a heap overflow in
  // ContactOperator::set_contacts while the file was being read.
  std::string p = payload_of(stepped_model());
  const std::size_t first = after_part(p, "contacts") + 8;
  poke<std::int32_t>(p, first + kContactVBlock, 40);
  expect_refused(p, "is damaged: contact 0's vertex block is 40, and there are 8 blocks");
  poke<std::int32_t>(p, first + kContactVBlock, -3);
  expect_refused(p, "contact 0's vertex block is -3");
}

TEST(CheckpointDamage, AnOutlineRunningPastTheVerticesIsRefused) {
  // vertex_start[1] = 0x7fffffff: the first step read far out of bounds.
  std::string p = payload_of(stepped_model());
  const std::size_t starts = after_part(p, "blocks") + 8;  // vertex_start's count, then its entries
  poke<std::int32_t>(p, starts + 4, 0x7fffffff);
  expect_refused(p, "block 0's outline runs from vertex 0 to 2147483647");
  poke<std::int32_t>(p, starts + 4, 2);
  expect_refused(p, "block 0's outline runs from vertex 0 to 2");
}

TEST(CheckpointDamage, FlagsAndEnumsOutOfRangeAreRefused) {
  std::string p = payload_of(stepped_model());
  const std::size_t first = after_part(p, "contacts") + 8;
  std::string flag = p;
  poke<std::uint8_t>(flag, first + kContactIntact, 2);
  expect_refused(flag, "a flag of value 2 (not 0 or 1)");
  std::string state = p;
  poke<std::uint8_t>(state, first + kContactState, 7);
  expect_refused(state, "an enum of value 7 (not one of its values)");
}

TEST(CheckpointDamage, ACountTheFileCannotHoldIsRefusedBeforeAllocating) {
  // The contacts' count raised to what the bytes left hold at one byte an
  // element (the old bound): a contact takes some 100 bytes in memory, so a
  // 42 MB file reached 4 GB. Now counted at a contact's own bytes.
  std::string p = payload_of(stepped_model());
  const std::size_t count = after_part(p, "contacts");
  const std::uint64_t contacts = peek<std::uint64_t>(p, count);
  const std::uint64_t left = p.size() - count - 8;
  ASSERT_GT(left / 2, contacts);
  poke<std::uint64_t>(p, count, left / 2);
  expect_refused(p, "its part 'contacts' ends early");
  poke<std::uint64_t>(p, count, ~std::uint64_t{0});
  expect_refused(p, "its part 'contacts' ends early");
}

TEST(CheckpointDamage, TextFromTheFileIsEscapedInMessages) {
  // A part's name replaced by a terminal escape sequence of the same length.
  std::string p = payload_of(stepped_model());
  const std::size_t at = after_part(p, "clock") - 5;
  p.replace(at, 5, "\x1b[2J\x07");
  try {
    checkpoint_from_bytes(checkpoint_file(p), "checkpoint 'x'");
    FAIL() << "accepted";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("found '\\x1b[2J\\x07'"), std::string::npos) << m;
    EXPECT_EQ(m.find('\x1b'), std::string::npos) << m;
  }
  EXPECT_EQ(printable("caf\xc3\xa9 \x9b 31m \xc2\x9b"), "caf\xc3\xa9 \\x9b 31m \\xc2\\x9b");
}

TEST(CheckpointDamage, AMaterialOrJointPastTheModelIsRefused) {
  const World w = stepped_model();
  std::string p = payload_of(w);
  // Blocks: vertex_start, vertices, centroid, area, sxx, syy, sxy, mass, material...
  std::size_t at = after_part(p, "blocks");
  auto skip_vector = [&](std::size_t element) {
    const auto n = peek<std::uint64_t>(p, at);
    at += 8 + n * element;
  };
  skip_vector(4), skip_vector(16), skip_vector(16);
  for (int k = 0; k < 5; ++k) skip_vector(8);
  poke<std::int32_t>(p, at + 8, 5);  // block 0's rock material
  expect_refused(p, "block 0's material is 5, and there are 1 rock materials");
}

TEST(CheckpointDamage, RestoredAccelerationTargetsContinueBitForBit) {
  // A displacement target driven by an acceleration history integrates it
  // twice; the second integral was not restored (an out-of-bounds read at
  // the next step). Reference: the same model stepped straight; tolerance:
  // none (equal state hashes).
  World straight = stepped_model();
  Checkpoint c = checkpoint_from_bytes(checkpoint_bytes(straight), "x");
  for (int i = 0; i < 5; ++i) straight.step(), c.world.step();
  EXPECT_EQ(c.world.state_hash(), straight.state_hash());
}

}  // namespace
}  // namespace dda
