// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Frames: a Scene drawn off-screen with OpenGL (OSMesa, Mesa's llvmpipe), then
// overlaid in software with the colour bar and text, as an RGB image.
//
//   dda::render::Renderer r;
//   dda::render::FrameOptions o;
//   o.field = dda::render::Field::SigmaYY;
//   r.render_to_png(scene, o, "out/syy.png");      // or: Frame f = r.render(scene, o);
//
// A Renderer owns one OpenGL context, created at the first render. It may be
// used from any thread, one thread at a time. For frames during a run, use
// FrameSequence (output/frame_sequence.hpp): it renders and encodes on a
// worker thread.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "raster/colormap.hpp"
#include "raster/image.hpp"
#include "scene/field.hpp"
#include "scene/scene.hpp"

namespace dda::render {

struct ValueRange {
  double min = 0, max = 0;  // SI units (Pa, m/s, m)
};

struct FrameOptions {
  int width = 1280, height = 720;  // pixels, 16 .. 8192
  Field field = Field::SigmaYY;
  std::optional<ColorMap> colormap;  // default: CoolWarm for signed fields, Viridis otherwise
  // Fixed colour range in SI units; without it the range comes from the
  // frame: ±max|value| for signed fields (so zero is the middle colour),
  // [0, max] for magnitudes. Values outside a fixed range get the end colours
  // and the colour bar an arrow at the end they pass.
  std::optional<ValueRange> range;
  // Said under the colour bar beside the frame's true min and max: "range:
  // fixed" for a set range, "range: grows" when it is a sequence's widest
  // range so far (set by FrameSequence), "range: frame" without one.
  bool range_grows = false;
  // World window (m) to show; without it, the model's bounds plus a 4 % margin.
  // The window is widened in x or y to keep the pixels square.
  std::optional<Box> view;
  // Deformation magnification: a vertex is drawn at initial + magnify ×
  // (current − initial). Needs Scene::initial_vertices when ≠ 1.
  double magnify = 1;

  bool show_edges = true;  // block outlines (joints) as thin lines
  double edge_width = 1;   // pixels
  Rgb edge_color{40, 40, 40};
  bool show_contacts = false;  // contact vertices: open white, sliding magenta, locked black
  double contact_size = 4;     // marker size (pixels)
  bool show_monitors = true;   // monitor points with their names
  bool show_velocity = false;  // velocity arrows at block centroids, with a reference arrow
  double arrow_scale = 0;      // arrow length (m) per (m/s); 0 → longest arrow = 6 % of the view
  bool show_scale = true;      // a scale bar (and the magnification when magnify ≠ 1)
  // Joints that broke (ContactMark::failed: bonded at the start, with
  // cohesion or tensile strength, and lost it since) drawn in red over the
  // edges; every other edge stays as the edges are drawn.
  bool show_joint_state = false;
  Rgb failed_joint_color{215, 25, 28};
  bool show_colorbar = true;  // colour bar with ticks, field name and unit
  bool show_info = true;      // top line: title or field, simulated time, step
  std::string title;          // replaces the field description on the top line
  Rgb background{255, 255, 255};
  int supersample = 1;  // 1..4: draw at k× size and average k×k pixels (smoother edges)

  // Throws dda::Error naming the bad option.
  void validate() const;
};

// Where things ended up in a frame: lets callers (and tests) map world points
// to pixels and find the colour bar.
struct FrameLayout {
  int width = 0, height = 0;
  PixelRect model;     // pixels the model view fills
  PixelRect colorbar;  // the colour ramp: top row = range.max, bottom row = range.min (empty if hidden)
  Box view;            // world window mapped onto `model` (after square-pixel widening)
  ValueRange range;    // colour range actually used (SI)
  // The frame's own extremes (SI, finite values only; both 0 without blocks),
  // marked on the colour bar and printed under it, whatever the range.
  ValueRange data;
  bool below = false, above = false;  // values beyond a set range: arrow ends on the bar
  std::string range_note;             // "range: frame" | "range: fixed" | "range: grows"
  ColorMap colormap = ColorMap::Viridis;
  double arrow_scale = 0;  // velocity arrows: m of arrow per m/s (0: none drawn)

  // World point → continuous pixel coordinates (x right, y down; pixel (i, j)
  // spans [i, i+1) × [j, j+1)).
  Vec2 to_pixel(const Vec2& world) const {
    return {model.x + (world.x() - view.xmin) / view.width() * model.w,
            model.y + (view.ymax - world.y()) / view.height() * model.h};
  }
  // Colour the frame uses for a value (SI) of its field.
  Rgb color_of(double value) const { return color_at(colormap, (value - range.min) / (range.max - range.min)); }
};

struct Frame {
  Image image;
  FrameLayout layout;
};

class Renderer {
 public:
  Renderer();
  ~Renderer();
  Renderer(Renderer&&) noexcept;
  Renderer& operator=(Renderer&&) noexcept;
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Draws the scene. Throws dda::Error for bad options, an inconsistent scene,
  // or when no OpenGL context can be created (OSMesa missing or failing); the
  // Renderer stays usable and retries the context at the next call.
  Frame render(const Scene& scene, const FrameOptions& options);

  // render + write_png. Throws dda::Error naming the path if it cannot be written.
  void render_to_png(const Scene& scene, const FrameOptions& options, const std::filesystem::path& path);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The colour range a frame takes from its scene when FrameOptions::range is
// not set: ±max|value| for signed fields, [0, max] for magnitudes (SI units;
// ±1 or [0, 1] display unit when every value is zero).
ValueRange frame_range(const Scene& scene, Field field);
// The world window a frame takes from its scene when FrameOptions::view is
// not set: the model's bounds as drawn (magnified) plus a 4 % margin.
Box frame_view(const Scene& scene, double magnify);
// The arrow scale (m per m/s) a frame takes when FrameOptions::arrow_scale is
// 0: the fastest block's arrow 6 % of the smaller side of `view`; 0 when
// nothing moves.
double auto_arrow_scale(const Scene& scene, const Box& view);

// Test hook: while set, creating an OpenGL context fails as if OSMesa were
// missing (so are contexts when the environment variable
// DDA_RENDER_DISABLE_OSMESA is set to anything but "0" or ""). A context
// that already exists is dropped at the next render.
void set_osmesa_disabled_for_testing(bool disabled);

}  // namespace dda::render
