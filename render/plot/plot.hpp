// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// History plots: line plots of recorded series, drawn in software (no OpenGL),
// for monitors and the validation report.
//
//   dda::render::PlotSpec p;
//   p.title = "σxx at the bar centre";
//   p.x_label = "time"; p.x_unit = "s";
//   p.y_label = "σxx"; p.y_unit = "MPa"; p.y_scale = 1e-6;   // data in Pa, axis in MPa
//   p.series.push_back({"g0 = 1e9", t, sxx});
//   dda::render::write_plot_png(p, "out/fig3.png");
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "raster/image.hpp"

namespace dda::render {

struct Series {
  std::string name;       // legend entry (empty: not in the legend)
  std::vector<double> x;  // same length as y; a non-finite point breaks the line
  std::vector<double> y;
  std::optional<Rgb> color;  // default: the next colour of a 10-colour palette
  double width = 2;          // line width (pixels)
};

// Best: the inside corner covering the fewest data points.
enum class LegendPosition { Best, TopRight, TopLeft, BottomRight, BottomLeft, None };

struct AxisRange {
  double min = 0, max = 0;  // in axis (display) units, i.e. after x_scale / y_scale
};

struct PlotSpec {
  std::string title;
  std::string x_label, x_unit;  // axis title is "label (unit)"
  std::string y_label, y_unit;
  double x_scale = 1, y_scale = 1;  // data × scale = axis value (e.g. 1e-6 for Pa → MPa)
  std::vector<Series> series;
  int width = 1000, height = 600;  // pixels, 64 .. 8192
  // Fixed axis ranges; without them, the data's range rounded outward to ticks.
  std::optional<AxisRange> x_range, y_range;
  LegendPosition legend = LegendPosition::Best;
  bool grid = true;
  Rgb background{255, 255, 255};

  void validate() const;  // dda::Error naming the problem
};

struct PlotLayout {
  PixelRect area;    // the plotting area inside the axes
  AxisRange x, y;    // axis ranges (display units)
  PixelRect legend;  // empty if no legend
  // Axis value → continuous pixel coordinate (x right, y down).
  double to_px(double xv) const { return area.x + (xv - x.min) / (x.max - x.min) * area.w; }
  double to_py(double yv) const { return area.y + (y.max - yv) / (y.max - y.min) * area.h; }
};

struct Plot {
  Image image;
  PlotLayout layout;
};

// The palette series take their default colours from, in order.
Rgb series_color(std::size_t index);

Plot render_plot(const PlotSpec& spec);
// render_plot + write_png; dda::Error naming the path if it cannot be written.
void write_plot_png(const PlotSpec& spec, const std::filesystem::path& path);

}  // namespace dda::render
