// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Frames that never mislead: a sequence's colours follow the data unless a
// range is declared; the colour bar marks the frame's true min and max and
// grows an arrow end where values pass a set range; the choice is printed;
// a joint is drawn failed only once it broke (never a cohesionless one).
// Each of these fails on a renderer that fixes the range from the first
// moving frame (later motion saturates), says nothing on the bar of values
// beyond it, and draws every cohesionless joint red from t = 0.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#endif
#include <stb/stb_image.h>

#include "frame/renderer.hpp"
#include "output/frame_sequence.hpp"
#include "scene/world_scene.hpp"
#include "world/world.hpp"

namespace fs = std::filesystem;
using dda::Vec2;
using dda::Vec3;
using namespace dda::render;

namespace {

// Two 1 m blocks side by side moving at `slow` and `fast` m/s.
Scene two_speeds(double slow, double fast, long step) {
  Scene s;
  const std::vector<Vec2> a{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, b{{2, 0}, {3, 0}, {3, 1}, {2, 1}};
  s.add_block(a, Vec3::Zero(), Vec2(slow, 0));
  s.add_block(b, Vec3::Zero(), Vec2(fast, 0));
  s.step = step;
  s.time = 1e-3 * static_cast<double>(step);
  return s;
}

FrameOptions velocity_frame() {
  FrameOptions o;
  o.field = Field::Velocity;
  o.width = 480, o.height = 300;
  return o;
}

int diff(Rgb a, Rgb b) { return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)}); }

Rgb png_pixel(const fs::path& file, const Vec2& px) {
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(file.c_str(), &w, &h, &n, 3);
  EXPECT_NE(data, nullptr) << file;
  if (!data) return {};
  const unsigned char* q = data + (static_cast<std::size_t>(px.y()) * w + static_cast<std::size_t>(px.x())) * 3;
  const Rgb c{q[0], q[1], q[2]};
  stbi_image_free(data);
  return c;
}

fs::path temp_dir(const std::string& name) {
  fs::path p = fs::temp_directory_path() / ("dda_honest_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

// Rows of the colour bar's arrow end (above the ramp when `up`) that hold
// the given colour at the bar's centre line.
int arrow_rows(const Frame& f, bool up, Rgb color) {
  const PixelRect& r = f.layout.colorbar;
  const int cx = r.x + r.w / 2;
  int rows = 0;
  for (int j = 2; j < r.w; ++j) {
    const int y = up ? r.y - j : r.bottom() + j;
    rows += diff(f.image.pixel(cx, y), color) <= 2;
  }
  return rows;
}

}  // namespace

// A sequence whose motion grows a hundredfold: in the late frame the two
// blocks (0.5 and 1 m/s) must get different colours. A range taken from the
// first moving frame (0.01 m/s) painted both in the end colour.
TEST(HonestFrames, SequenceColoursFollowTheDataByDefault) {
  const fs::path dir = temp_dir("follow");
  SequenceOptions so;
  so.folder = dir;
  so.frame = velocity_frame();
  {
    FrameSequence seq(so);
    seq.capture(two_speeds(0.005, 0.01, 0));
    seq.capture(two_speeds(0.5, 1.0, 10));
    seq.flush();
  }
  FrameOptions o = velocity_frame();
  o.view = frame_view(two_speeds(0, 0, 0), 1);
  const Scene late = two_speeds(0.5, 1.0, 10);
  const Frame expected = Renderer().render(late, o);
  EXPECT_EQ(expected.layout.range_note, "range: frame");
  const fs::path file = dir / "velocity_00001.png";
  const Rgb slow = png_pixel(file, expected.layout.to_pixel(late.centroids[0]));
  const Rgb fast = png_pixel(file, expected.layout.to_pixel(late.centroids[1]));
  EXPECT_GT(diff(slow, fast), 40) << "0.5 and 1 m/s drawn alike: the colour range saturates";
  EXPECT_LE(diff(fast, color_at(ColorMap::Viridis, 1.0)), 2) << "the fastest block takes the top colour";
  EXPECT_LE(diff(slow, color_at(ColorMap::Viridis, 0.5)), 2) << "half the speed, half way up the map";
  fs::remove_all(dir);
}

// The frame's true extremes on a bar whose set range they pass: the
// extremes as they are, an arrow end in the end colour on each side passed,
// none on a side not passed; without a set range no arrows at all.
TEST(HonestFrames, ColourBarShowsTrueExtremesAndOverflow) {
  const Scene s = two_speeds(0.3, 2.5, 0);
  FrameOptions o = velocity_frame();
  o.range = ValueRange{0.5, 1.0};
  Renderer r;
  const Frame f = r.render(s, o);
  EXPECT_DOUBLE_EQ(f.layout.data.min, 0.3);
  EXPECT_DOUBLE_EQ(f.layout.data.max, 2.5);
  EXPECT_TRUE(f.layout.above);
  EXPECT_TRUE(f.layout.below);
  EXPECT_EQ(f.layout.range_note, "range: fixed");
  EXPECT_GT(arrow_rows(f, true, color_at(ColorMap::Viridis, 1.0)), 5) << "no arrow end above the bar";
  EXPECT_GT(arrow_rows(f, false, color_at(ColorMap::Viridis, 0.0)), 5) << "no arrow end below the bar";

  const Frame inside = r.render(two_speeds(0.6, 0.9, 0), o);
  EXPECT_FALSE(inside.layout.above);
  EXPECT_FALSE(inside.layout.below);
  EXPECT_EQ(arrow_rows(inside, true, color_at(ColorMap::Viridis, 1.0)), 0) << "an arrow end without overflow";
  EXPECT_EQ(arrow_rows(inside, false, color_at(ColorMap::Viridis, 0.0)), 0) << "an arrow end without overflow";

  o.range.reset();
  const Frame own = r.render(s, o);
  EXPECT_EQ(own.layout.range_note, "range: frame");
  EXPECT_FALSE(own.layout.above || own.layout.below);
  EXPECT_DOUBLE_EQ(own.layout.data.max, 2.5);
  EXPECT_EQ(own.layout.range.max, 2.5);
}

// The extremes are marked beside the ramp and printed under it: a dark
// pointer left of the ramp where the max sits (none where nothing is), and
// text in the rows under the ramp.
TEST(HonestFrames, ExtremesAreMarkedAndPrinted) {
  FrameOptions o = velocity_frame();
  o.width = 640, o.height = 400;
  o.range = ValueRange{0, 4};
  const Frame f = Renderer().render(two_speeds(1.0, 3.0, 0), o);
  const PixelRect& r = f.layout.colorbar;
  auto dark_left_of_ramp = [&](double v) {
    const int row = r.y + static_cast<int>(std::lround((1 - v / 4) * (r.h - 1)));
    const Rgb c = f.image.pixel(r.x - 3, row);
    return c.r + c.g + c.b < 60;
  };
  EXPECT_TRUE(dark_left_of_ramp(3.0)) << "no pointer at the frame's max (3 of 0..4)";
  EXPECT_TRUE(dark_left_of_ramp(1.0)) << "no pointer at the frame's min (1 of 0..4)";
  EXPECT_FALSE(dark_left_of_ramp(2.0)) << "a pointer where no extreme is";
  int inked = 0;
  for (int y = r.bottom() + 2; y < f.layout.height; ++y)
    for (int x = r.x; x < f.layout.width; ++x) {
      const Rgb c = f.image.pixel(x, y);
      inked += c.r + c.g + c.b < 600;
    }
  EXPECT_GT(inked, 100) << "no text under the colour bar (max, min, range)";
}

namespace {

// A 1 m block on a fixed 1 m base, the joint between them of material
// `joint`; no gravity. Block 1 is the upper one.
dda::World stacked(const dda::JointMaterial& joint) {
  dda::Controls c;
  c.gravity = Vec2(0, 0);
  c.g1 = 1e-4;
  dda::World w(c);
  const int rock = w.add_rock_material({});
  const int j = w.add_joint_material(joint);
  w.add_block({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, rock, {j, j, j, j});
  w.add_block({{0, 1}, {1, 1}, {1, 2}, {0, 2}}, rock, {j, j, j, j});
  w.add_fixed_point(0, {0, 0});
  w.add_fixed_point(0, {1, 0});
  return w;
}

int failed_marks(const Scene& s) {
  int n = 0;
  for (const ContactMark& m : s.contacts) n += m.failed;
  return n;
}

int bonded(const dda::World& w) {
  int n = 0;
  for (const dda::Contact& c : w.contacts()) n += c.bonded;
  return n;
}

// Red pixels along the joint (y = 1), drawn with joints = true.
int red_along_joint(const Scene& s) {
  FrameOptions o;
  o.field = Field::None;
  o.width = 320, o.height = 320;
  o.show_joint_state = true;
  const Frame f = Renderer().render(s, o);
  int red = 0;
  for (double x = 0.1; x < 0.95; x += 0.05) {
    const Vec2 p = f.layout.to_pixel({x, 1});
    for (int dy = -2; dy <= 2; ++dy) {
      const Rgb c = f.image.pixel(static_cast<int>(p.x()), static_cast<int>(p.y()) + dy);
      red += c.r > 180 && c.g < 80 && c.b < 80;
    }
  }
  return red;
}

}  // namespace

// A joint without cohesion or tensile strength has nothing to lose: it is
// never drawn failed, though its contacts are not "intact".
TEST(HonestFrames, CohesionlessJointIsNeverDrawnFailed) {
  dda::World w = stacked({30, 0, 0});
  for (int i = 0; i < 5; ++i) w.step();
  ASSERT_GT(bonded(w), 0) << "the blocks should touch from the start";
  const Scene s = snapshot(w);
  EXPECT_EQ(failed_marks(s), 0);
  EXPECT_EQ(red_along_joint(s), 0) << "a cohesionless joint drawn red";
}

// A joint with tensile strength σt = 1 kPa (1 kN over the 1 m joint): drawn
// as the edges are while it holds, red once a 20 kN pull broke it.
TEST(HonestFrames, BondedJointIsDrawnFailedOnlyAfterItBroke) {
  dda::World w = stacked({30, 1e3, 1e3});
  for (int i = 0; i < 5; ++i) w.step();
  ASSERT_GT(bonded(w), 0);
  Scene s = snapshot(w);
  EXPECT_EQ(failed_marks(s), 0) << "failed before anything pulled";
  EXPECT_EQ(red_along_joint(s), 0);
  w.add_point_load(1, {0.5, 1.5}, {0, 2e4});
  int steps = 0;
  while (failed_marks(snapshot(w)) == 0 && steps < 200) w.step(), ++steps;
  s = snapshot(w);
  EXPECT_GT(failed_marks(s), 0) << "the pulled joint never broke in 200 steps";
  EXPECT_GT(red_along_joint(s), 0) << "the broken joint is not drawn red";
}
