// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Software drawing on an Image: anti-aliased strokes, outlines, markers, and
// "nice" axis ticks. Used for plots and for the overlays of frames (colour
// bar, labels), so neither needs OpenGL.
#include <string>
#include <vector>

#include "raster/image.hpp"

namespace dda::render {

struct PointF {
  double x = 0, y = 0;  // pixel coordinates: x right, y down; pixel (i, j) covers [i, i+1) × [j, j+1)
};

// Draws a polyline of the given width with anti-aliased edges, clipped to
// `clip`. A point with a non-finite coordinate breaks the line there. Where
// the line crosses itself it is not darkened twice.
void stroke_polyline(Image& image, const std::vector<PointF>& points, double width, Rgb color, const PixelRect& clip);

inline void stroke_line(Image& image, PointF a, PointF b, double width, Rgb color, const PixelRect& clip) {
  stroke_polyline(image, {a, b}, width, color, clip);
}

// One-pixel outline just inside the rectangle.
void outline_rect(Image& image, const PixelRect& r, Rgb color);

// Axis ticks at 1, 2 or 5 × 10^k steps covering [lo, hi] (about `target`
// of them), with labels. When the values are very large or small the labels
// are given in units of 10^exponent and `multiplier` says so ("×1e-5"); else it
// is empty.
struct Ticks {
  std::vector<double> values;
  std::vector<std::string> labels;
  std::string multiplier;
};
Ticks nice_ticks(double lo, double hi, int target = 6);

// Rounds [lo, hi] outward to the tick step nice_ticks would choose.
void nice_range(double& lo, double& hi, int target = 6);

// Formats a number compactly for on-image text ("0.0123", "1.5e+06").
std::string format_number(double v, int significant = 4);

}  // namespace dda::render
