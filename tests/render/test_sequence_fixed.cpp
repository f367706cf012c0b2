// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Animation-safe sequences: a block falling 4.9 m must be seen to fall (the
// view is fixed from the first frame, not re-fitted to the moving block) and
// a declared colour range must read the same in every frame (its ticks and
// labels; the marks of each frame's own min and max move). The same frames
// with `fixed = false` and no declared range re-fit, which the checks must
// notice: the test can fail.
#include <gtest/gtest.h>
#include <unistd.h>

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

namespace fs = std::filesystem;
using dda::Vec2;
using dda::Vec3;
using namespace dda::render;

namespace {

constexpr double kG = 9.81;

// A ground block and a 1 m block falling from y = 6 m: at time t it has
// dropped g t²/2 and moves at g t downwards.
Scene falling(double t, long step) {
  Scene s;
  const std::vector<Vec2> ground{{-2, 0}, {3, 0}, {3, 0.5}, {-2, 0.5}};
  s.add_block(ground);
  const double y = 6 - 0.5 * kG * t * t;
  const std::vector<Vec2> block{{0, y}, {1, y}, {1, y + 1}, {0, y + 1}};
  s.add_block(block, Vec3::Zero(), Vec2(0, -kG * t), Vec2(0, y - 6));
  s.time = t;
  s.step = step;
  return s;
}

struct Png {
  int w = 0, h = 0;
  std::vector<unsigned char> rgb;
  Rgb at(int x, int y) const {
    const unsigned char* q = &rgb[(static_cast<std::size_t>(y) * w + x) * 3];
    return {q[0], q[1], q[2]};
  }
};

Png load(const fs::path& p) {
  Png png;
  int n = 0;
  unsigned char* data = stbi_load(p.c_str(), &png.w, &png.h, &n, 3);
  if (data) png.rgb.assign(data, data + static_cast<std::size_t>(png.w) * png.h * 3);
  stbi_image_free(data);
  return png;
}

const double kTimes[] = {0, 0.4, 0.8};  // drops 0, 0.78 m, 3.14 m

constexpr ValueRange kDeclared{0, 8};  // m/s: the fall reaches 7.8

std::vector<Png> run_sequence(const fs::path& dir, bool fixed) {
  SequenceOptions so;
  so.folder = dir;
  so.fixed = fixed;
  if (fixed) so.frame.range = kDeclared;
  so.frame.field = Field::Velocity;
  so.frame.width = 320, so.frame.height = 240;
  {
    FrameSequence seq(so);
    for (int i = 0; i < 3; ++i) seq.capture(falling(kTimes[i], 10 * i));
    seq.flush();
  }
  std::vector<Png> out;
  for (int i = 0; i < 3; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "velocity_%05d.png", i);
    out.push_back(load(dir / name));
  }
  return out;
}

// The layout every fixed frame shares: the first frame's view, the
// declared range.
FrameLayout fixed_layout() {
  FrameOptions o;
  o.field = Field::Velocity;
  o.width = 320, o.height = 240;
  o.view = frame_view(falling(0, 0), 1);
  o.range = kDeclared;
  return Renderer().render(falling(kTimes[1], 10), o).layout;
}

// The colour bar's ticks and their labels: right of the ramp, over its height.
bool same_colour_bar(const Png& a, const Png& b, const FrameLayout& L) {
  for (int y = L.colorbar.y; y < L.colorbar.bottom(); ++y)
    for (int x = L.colorbar.right() + 1; x < L.width; ++x)
      if (!(a.at(x, y) == b.at(x, y))) return false;
  return true;
}

bool is_background(const Png& p, const Vec2& px) {
  const Rgb c = p.at(static_cast<int>(px.x()), static_cast<int>(px.y()));
  return c.r == 255 && c.g == 255 && c.b == 255;
}

fs::path temp_dir(const std::string& name) {
  fs::path p = fs::temp_directory_path() / ("dda_render_seq_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

}  // namespace

TEST(FixedSequence, FallingBlockMovesAndColourBarStays) {
  const fs::path dir = temp_dir("fixed");
  const std::vector<Png> f = run_sequence(dir, true);
  ASSERT_EQ(f[0].w, 320);
  ASSERT_EQ(f[2].w, 320);
  const FrameLayout L = fixed_layout();
  for (int i = 1; i < 3; ++i)
    EXPECT_TRUE(same_colour_bar(f[0], f[i], L)) << "frame " << i << "'s colour bar differs from frame 0's";
  // Where the block is drawn: at its centre of each frame's time, and its
  // start is empty once it has fallen 3.14 m.
  for (int i = 0; i < 3; ++i) {
    const double y = 6.5 - 0.5 * kG * kTimes[i] * kTimes[i];
    EXPECT_FALSE(is_background(f[i], L.to_pixel({0.5, y}))) << "frame " << i << ": the block is not where it fell to";
  }
  EXPECT_TRUE(is_background(f[2], L.to_pixel({0.5, 6.5}))) << "frame 2 still shows the block at its start";
  EXPECT_GT(L.to_pixel({0.5, 6.5 - 0.5 * kG * 0.64}).y() - L.to_pixel({0.5, 6.5}).y(), 20)
      << "the drop should span many pixels";
  fs::remove_all(dir);
}

TEST(FixedSequence, RefittingFramesAreCaughtByTheSameChecks) {
  const fs::path dir = temp_dir("refit");
  const std::vector<Png> f = run_sequence(dir, false);
  const FrameLayout L = fixed_layout();
  EXPECT_FALSE(same_colour_bar(f[1], f[2], L)) << "re-fitted ranges (1 → ~3.9 → ~7.8 m/s) should change the bar";
  EXPECT_FALSE(is_background(f[2], L.to_pixel({0.5, 6.5})) &&
               !is_background(f[2], L.to_pixel({0.5, 6.5 - 0.5 * kG * 0.64})))
      << "a re-fitted view cannot show the block where a fixed view does";
  fs::remove_all(dir);
}

TEST(FixedSequence, ScaleBarMagnificationAndFailedJoints) {
  Scene s = falling(0, 0);
  s.contacts.push_back({1, 0, dda::ContactState::Sliding, 0, 2, true});  // a failed joint on the ground's top edge
  FrameOptions o;
  o.width = 320, o.height = 240;
  o.field = Field::None;
  o.show_joint_state = true;
  Renderer r;
  const Frame with = r.render(s, o);
  o.show_scale = false;
  o.show_joint_state = false;
  const Frame without = r.render(s, o);
  // The scale bar: black pixels at the bottom left of the model view.
  const FrameLayout& L = with.layout;
  int black = 0;
  for (int y = L.model.bottom() - 20; y < L.model.bottom(); ++y)
    for (int x = L.model.x; x < L.model.x + L.model.w / 3; ++x) {
      const Rgb c = with.image.pixel(x, y), d = without.image.pixel(x, y);
      black += c.r < 40 && c.g < 40 && c.b < 40 && !(d.r < 40 && d.g < 40 && d.b < 40);
    }
  EXPECT_GT(black, 20) << "no scale bar drawn";
  // The failed joint: red along the ground's top edge (y = 0.5), not without.
  const Vec2 mid = L.to_pixel({0.5, 0.5});
  int red = 0;
  for (int dy = -2; dy <= 2; ++dy) {
    const Rgb c = with.image.pixel(static_cast<int>(mid.x()), static_cast<int>(mid.y()) + dy);
    red += c.r > 180 && c.g < 80 && c.b < 80;
  }
  EXPECT_GT(red, 0) << "the failed joint is not drawn in red";
}
