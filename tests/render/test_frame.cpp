// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Frames: colours at known places, the colour bar, determinism, options,
// deformation magnification, concave blocks, and the PNG on disk.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
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

#include "core/error.hpp"
#include "frame/renderer.hpp"
#include "frame/triangulate.hpp"
#include "raster/image.hpp"

namespace fs = std::filesystem;
using dda::Vec2;
using dda::Vec3;
using namespace dda::render;

namespace {

// Largest per-channel difference.
int diff(Rgb a, Rgb b) { return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)}); }

std::string str(Rgb c) {
  return "(" + std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b) + ")";
}

Rgb pixel_at(const Frame& f, const Vec2& world) {
  const Vec2 p = f.layout.to_pixel(world);
  return f.image.pixel(static_cast<int>(std::floor(p.x())), static_cast<int>(std::floor(p.y())));
}

fs::path temp_dir(const std::string& name) {
  fs::path p = fs::temp_directory_path() / ("dda_render_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

// A 4 x 3 grid of 1 m squares far from the origin (at x = 500, y = -200, to
// catch precision loss), σxx from -4 to +6.5 MPa, plus a concave L-shaped
// block to the right with σxx = 2 MPa. The largest |σxx| is 6.5 MPa.
struct TestScene {
  Scene scene;
  std::vector<double> sxx;
  Vec2 notch;  // a point in the L's notch: outside every block
};

TestScene make_scene() {
  TestScene t;
  const double x0 = 500, y0 = -200;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) {
      const double v = (-4.0 + 0.875 * (j * 4 + i)) * 1e6;  // -4 .. +5.625 MPa
      const std::vector<Vec2> q{{x0 + i, y0 + j}, {x0 + i + 1, y0 + j}, {x0 + i + 1, y0 + j + 1}, {x0 + i, y0 + j + 1}};
      t.scene.add_block(q, Vec3(v, -v / 2, 0.3e6), Vec2(0.1 * i, -0.05 * j), Vec2(0.001 * i, 0));
      t.sxx.push_back(v);
    }
  // L: 2 m wide foot, 3 m tall stem 1 m wide; centroid (x0+5.7, y0+1.3) is
  // inside. Listed from the inner corner's neighbour (7, 1), from which a plain
  // triangle fan would cover part of the notch.
  const std::vector<Vec2> L{{x0 + 7, y0 + 1}, {x0 + 6, y0 + 1}, {x0 + 6, y0 + 3},
                            {x0 + 5, y0 + 3}, {x0 + 5, y0},     {x0 + 7, y0}};
  t.scene.add_block(L, Vec3(2e6, 0, 0));
  t.sxx.push_back(2e6);
  // Block with the extreme value, -6.5 MPa.
  const std::vector<Vec2> q{{x0, y0 - 2}, {x0 + 1, y0 - 2}, {x0 + 1, y0 - 1}, {x0, y0 - 1}};
  t.scene.add_block(q, Vec3(-6.5e6, 0, 0));
  t.sxx.push_back(-6.5e6);
  t.notch = {x0 + 6.2, y0 + 2.2};
  t.scene.time = 0.125;
  t.scene.step = 250;
  return t;
}

FrameOptions sxx_options() {
  FrameOptions o;
  o.width = 640;
  o.height = 400;
  o.field = Field::SigmaXX;
  return o;
}

}  // namespace

TEST(Frame, PixelAtEachCentroidHasTheColourOfTheBlocksValue) {
  const TestScene t = make_scene();
  Renderer r;
  const Frame f = r.render(t.scene, sxx_options());
  ASSERT_EQ(f.image.width(), 640);
  ASSERT_EQ(f.image.height(), 400);
  // Automatic range of a signed field: symmetric about zero.
  EXPECT_DOUBLE_EQ(f.layout.range.min, -6.5e6);
  EXPECT_DOUBLE_EQ(f.layout.range.max, 6.5e6);
  EXPECT_EQ(f.layout.colormap, ColorMap::CoolWarm);
  for (std::size_t b = 0; b < t.scene.block_count(); ++b) {
    // Expected colour computed from the stated range, not from the layout.
    const Rgb want = color_at(ColorMap::CoolWarm, (t.sxx[b] + 6.5e6) / 13e6);
    const Rgb got = pixel_at(f, t.scene.centroids[b]);
    EXPECT_LE(diff(got, want), 2) << "block " << b << ": got " << str(got) << ", want " << str(want);
  }
  // The extreme blocks get the map's end colour; different values differ.
  EXPECT_EQ(pixel_at(f, t.scene.centroids.back()), color_at(ColorMap::CoolWarm, 0.0));
  EXPECT_NE(pixel_at(f, t.scene.centroids[0]), pixel_at(f, t.scene.centroids[11]));
}

TEST(Frame, BackgroundOutsideTheBlocksIncludingTheNotchOfAConcaveBlock) {
  const TestScene t = make_scene();
  FrameOptions o = sxx_options();
  o.background = {250, 240, 230};
  Renderer r;
  const Frame f = r.render(t.scene, o);
  EXPECT_EQ(pixel_at(f, t.notch), o.background) << "concave block filled across its notch";
  const PixelRect& m = f.layout.model;
  for (auto [x, y] : {std::pair{m.x + 1, m.y + 1},
                      {m.right() - 2, m.y + 1},
                      {m.x + 1, m.bottom() - 2},
                      {m.right() - 2, m.bottom() - 2}})
    EXPECT_EQ(f.image.pixel(x, y), o.background) << "model corner " << x << "," << y;
  EXPECT_EQ(f.image.pixel(0, f.image.height() - 1), o.background);
  EXPECT_EQ(f.image.pixel(f.image.width() - 1, f.image.height() - 1), o.background);
}

TEST(Frame, ColourBarSpansTheStatedRange) {
  const TestScene t = make_scene();
  FrameOptions o = sxx_options();
  o.field = Field::SigmaYY;
  o.range = ValueRange{-1e6, 3e6};
  Renderer r;
  const Frame f = r.render(t.scene, o);
  EXPECT_EQ(f.layout.range.min, -1e6);
  EXPECT_EQ(f.layout.range.max, 3e6);
  const PixelRect& bar = f.layout.colorbar;
  ASSERT_FALSE(bar.empty());
  ASSERT_GE(bar.h, 100);
  const int cx = bar.x + bar.w / 2;
  EXPECT_EQ(f.image.pixel(cx, bar.y), color_at(ColorMap::CoolWarm, 1.0)) << "top of the bar = range max";
  EXPECT_EQ(f.image.pixel(cx, bar.bottom() - 1), color_at(ColorMap::CoolWarm, 0.0)) << "bottom of the bar = range min";
  // Zero sits a quarter of the way up the bar.
  const int zero_row = bar.y + static_cast<int>(std::lround(0.75 * (bar.h - 1)));
  EXPECT_LE(diff(f.image.pixel(cx, zero_row), color_at(ColorMap::CoolWarm, 0.25)), 3);
  // Outside the bar: not bar colours (the bar has a frame).
  EXPECT_NE(f.image.pixel(cx, bar.y - 1), color_at(ColorMap::CoolWarm, 1.0));
  // Values beyond a fixed range take the end colours: σyy = +2 MPa is the
  // largest here (block 0), σyy = -2.8125 MPa (block 11) is below -1 MPa.
  EXPECT_LE(diff(pixel_at(f, t.scene.centroids[0]), color_at(ColorMap::CoolWarm, (2e6 + 1e6) / 4e6)), 2);
  EXPECT_EQ(pixel_at(f, t.scene.centroids[11]), color_at(ColorMap::CoolWarm, 0.0));
}

TEST(Frame, MagnitudeFieldsUseViridisFromZero) {
  const TestScene t = make_scene();
  FrameOptions o = sxx_options();
  o.field = Field::Velocity;
  Renderer r;
  const Frame f = r.render(t.scene, o);
  EXPECT_EQ(f.layout.colormap, ColorMap::Viridis);
  EXPECT_DOUBLE_EQ(f.layout.range.min, 0);
  const double vmax = Vec2(0.3, -0.1).norm();  // block 11
  EXPECT_DOUBLE_EQ(f.layout.range.max, vmax);
  for (std::size_t b = 0; b < t.scene.block_count(); ++b) {
    const Rgb want = color_at(ColorMap::Viridis, t.scene.velocity[b].norm() / vmax);
    EXPECT_LE(diff(pixel_at(f, t.scene.centroids[b]), want), 2) << "block " << b;
  }
  const PixelRect& bar = f.layout.colorbar;
  EXPECT_EQ(f.image.pixel(bar.x + 1, bar.y), color_at(ColorMap::Viridis, 1.0));
  EXPECT_EQ(f.image.pixel(bar.x + 1, bar.bottom() - 1), color_at(ColorMap::Viridis, 0.0));
}

TEST(Frame, SameFrameRenderedTwiceIsIdentical) {
  const TestScene t = make_scene();
  FrameOptions o = sxx_options();
  o.show_contacts = true;
  o.show_velocity = true;
  Scene s = t.scene;
  s.contacts.push_back({0, 1, dda::ContactState::Sliding});
  s.monitors.push_back({"centre", {502, -198.5}, {0, 0}});
  Renderer r1;
  const Frame a = r1.render(s, o);
  const Frame b = r1.render(s, o);
  Renderer r2;
  const Frame c = r2.render(s, o);
  EXPECT_TRUE(a.image == b.image);
  EXPECT_TRUE(a.image == c.image);
  EXPECT_EQ(encode_png(a.image), encode_png(c.image));
  // A different frame size in between does not disturb the next frame.
  FrameOptions small = o;
  small.width = 200, small.height = 150;
  r1.render(s, small);
  EXPECT_TRUE(r1.render(s, o).image == a.image);
}

TEST(Frame, ExplicitViewWindowMapsWorldToPixels) {
  const TestScene t = make_scene();
  FrameOptions o = sxx_options();
  o.show_colorbar = false;
  o.show_info = false;
  Renderer r;
  Frame f = r.render(t.scene, o);
  // Choose a window with the model rectangle's aspect, so it is kept as given.
  const PixelRect m = f.layout.model;
  const double h = 2.0, w = h * m.w / m.h;
  o.view = Box{501.0, -199.5, 501.0 + w, -199.5 + h};
  f = r.render(t.scene, o);
  EXPECT_NEAR(f.layout.view.xmin, 501.0, 1e-9);
  EXPECT_NEAR(f.layout.view.xmax, 501.0 + w, 1e-9);
  // Block 5 (i=1, j=1) spans x 501..502, y -199..-198: its centre is at
  // pixel x = m.x + 0.5/w·m.w, y = m.y + (0.5 / h)·m.h from the top of the window (-197.5).
  const double px = m.x + 0.5 / w * m.w, py = m.y + (-197.5 - (-198.5)) / h * m.h;
  const Rgb want = color_at(ColorMap::CoolWarm, (t.sxx[5] + 6.5e6) / 13e6);
  EXPECT_LE(diff(f.image.pixel(static_cast<int>(px), static_cast<int>(py)), want), 2);
}

TEST(Frame, MagnifiedDeformationMovesBlocksByFactorTimesDisplacement) {
  // One 1 m block that moved 0.1 m right since the start.
  Scene s;
  const std::vector<Vec2> start{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  std::vector<Vec2> now = start;
  for (Vec2& v : now) v.x() += 0.1;
  s.add_block(now, Vec3(1e6, 0, 0), Vec2::Zero(), Vec2(0.1, 0), start);
  // A fixed block far right keeps the view wide.
  const std::vector<Vec2> far{{6, 0}, {7, 0}, {7, 1}, {6, 1}};
  s.add_block(far, Vec3(-1e6, 0, 0));
  FrameOptions o = sxx_options();
  o.magnify = 20;  // drawn at 0 + 20·0.1 = 2 m right of the start
  o.view = Box{-1, -3, 8, 4};
  Renderer r;
  const Frame f = r.render(s, o);
  const Rgb block = color_at(ColorMap::CoolWarm, 1.0);
  EXPECT_EQ(pixel_at(f, {2.5, 0.5}), block) << "magnified position";
  EXPECT_EQ(pixel_at(f, {0.5, 0.5}), o.background) << "the true position is left empty";
  // Without initial vertices, the centroid displacement is magnified instead: same here.
  Scene s2 = s;
  s2.initial_vertices.clear();
  EXPECT_EQ(pixel_at(r.render(s2, o), {2.5, 0.5}), block);
}

TEST(Frame, EveryFieldAndOverlayRenders) {
  TestScene t = make_scene();
  t.scene.contacts = {
      {0, 2, dda::ContactState::Open}, {1, 2, dda::ContactState::Sliding}, {2, 2, dda::ContactState::Locked}};
  t.scene.monitors.push_back({"A", {501.5, -198.5}, {0, 0}});
  Renderer r;
  for (const FieldInfo& info : all_fields()) {
    FrameOptions o = sxx_options();
    o.field = info.field;
    o.show_contacts = o.show_velocity = true;
    o.supersample = 2;
    o.magnify = 5;
    EXPECT_NO_THROW(r.render(t.scene, o)) << info.key;
    EXPECT_EQ(parse_field(info.key), info.field);
  }
}

TEST(Frame, FieldValues) {
  Scene s;
  const std::vector<Vec2> q{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  s.add_block(q, Vec3(-3e6, 1e6, 2e6), Vec2(3, 4), Vec2(-6, 8));
  // σ1 = c + r with c = -1 MPa, r = sqrt(2² + 2²) MPa.
  EXPECT_NEAR(field_value(s, 0, Field::SigmaMajor), -1e6 + std::sqrt(8.0) * 1e6, 1e-6);
  EXPECT_NEAR(field_value(s, 0, Field::VonMises), std::sqrt(9.0 + 3 + 1 + 12) * 1e6, 1e-6);
  EXPECT_DOUBLE_EQ(field_value(s, 0, Field::TauXY), 2e6);
  EXPECT_DOUBLE_EQ(field_value(s, 0, Field::Velocity), 5);
  EXPECT_DOUBLE_EQ(field_value(s, 0, Field::Displacement), 10);
  EXPECT_EQ(default_colormap(Field::SigmaXX), ColorMap::CoolWarm);
  EXPECT_EQ(default_colormap(Field::VonMises), ColorMap::Viridis);
  try {
    parse_field("sigma_zz");
    FAIL() << "no error";
  } catch (const dda::Error& e) {
    EXPECT_NE(std::string(e.what()).find("sigma_zz"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("von_mises"), std::string::npos) << "lists the known fields";
  }
}

TEST(Frame, BadOptionsAndScenesAreClearErrors) {
  const TestScene t = make_scene();
  Renderer r;
  FrameOptions o = sxx_options();
  o.width = 100000;
  EXPECT_THROW(r.render(t.scene, o), dda::Error);
  o = sxx_options();
  o.range = ValueRange{1, 1};
  EXPECT_THROW(r.render(t.scene, o), dda::Error);
  Scene bad = t.scene;
  bad.stress.pop_back();
  EXPECT_THROW(r.render(bad, sxx_options()), dda::Error);
  bad = t.scene;
  bad.vertices[3].x() = std::nan("");
  EXPECT_THROW(r.render(bad, sxx_options()), dda::Error);
  // The renderer carries on after errors.
  EXPECT_NO_THROW(r.render(t.scene, sxx_options()));
}

TEST(Frame, EmptySceneRendersBackground) {
  Renderer r;
  FrameOptions o = sxx_options();
  const Frame f = r.render(Scene{}, o);
  EXPECT_EQ(f.image.pixel(f.layout.model.x + f.layout.model.w / 2, f.layout.model.y + f.layout.model.h / 2),
            o.background);
}

TEST(Triangulate, CoversConcaveAndClockwisePolygons) {
  auto area = [](const std::vector<Vec2>& p, const std::vector<std::array<int, 3>>& tris) {
    double a = 0;
    for (const auto& t : tris) {
      const Vec2 u = p[t[1]] - p[t[0]], v = p[t[2]] - p[t[0]];
      a += std::abs(u.x() * v.y() - u.y() * v.x()) / 2;
    }
    return a;
  };
  // Comb: area 5×1 base + 3 teeth of 1×2 = 11.
  std::vector<Vec2> comb{{0, 0}, {5, 0}, {5, 3}, {4, 3}, {4, 1}, {3, 1},
                         {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  std::vector<std::array<int, 3>> tris;
  triangulate(comb, tris);
  EXPECT_EQ(tris.size(), comb.size() - 2);
  EXPECT_NEAR(area(comb, tris), 11, 1e-12);
  std::vector<Vec2> cw(comb.rbegin(), comb.rend());
  tris.clear();
  triangulate(cw, tris);
  EXPECT_NEAR(area(cw, tris), 11, 1e-12);
}

TEST(Png, FileIsUprightAndDecodesToTheSamePixels) {
  const fs::path dir = temp_dir("png");
  // A frame whose upper half holds one red-ish block: the PNG's top rows must show it.
  Scene s;
  const std::vector<Vec2> top{{0, 1}, {4, 1}, {4, 2}, {0, 2}};
  const std::vector<Vec2> bottom{{0, 0}, {4, 0}, {4, 0.5}, {0, 0.5}};
  s.add_block(top, Vec3(0, 5e6, 0));
  s.add_block(bottom, Vec3(0, -5e6, 0));
  Renderer r;
  FrameOptions o;
  o.width = 320, o.height = 240;
  o.show_colorbar = o.show_info = false;
  const Frame f = r.render(s, o);
  const fs::path file = dir / "upright.png";
  write_png(f.image, file);
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(file.c_str(), &w, &h, &n, 3);
  ASSERT_NE(data, nullptr);
  ASSERT_EQ(w, 320);
  ASSERT_EQ(h, 240);
  const Vec2 p_top = f.layout.to_pixel({2, 1.5}), p_bot = f.layout.to_pixel({2, 0.25});
  ASSERT_LT(p_top.y(), p_bot.y());
  auto at = [&](const Vec2& p) {
    const unsigned char* q = data + (static_cast<int>(p.y()) * w + static_cast<int>(p.x())) * 3;
    return Rgb{q[0], q[1], q[2]};
  };
  EXPECT_EQ(at(p_top), color_at(ColorMap::CoolWarm, 1.0)) << "tension block (top of the model) at the top of the PNG";
  EXPECT_EQ(at(p_bot), color_at(ColorMap::CoolWarm, 0.0));
  EXPECT_EQ(0, std::memcmp(data, f.image.data(), f.image.size_bytes()));
  stbi_image_free(data);
  fs::remove_all(dir);
}
