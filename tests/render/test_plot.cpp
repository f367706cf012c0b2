// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// History plots: geometry of a known curve, legend, ranges, ticks, errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "core/error.hpp"
#include "core/types.hpp"
#include "plot/plot.hpp"
#include "raster/canvas.hpp"

using namespace dda::render;

namespace {

bool near_color(Rgb a, Rgb b, int tol) {
  return std::abs(a.r - b.r) <= tol && std::abs(a.g - b.g) <= tol && std::abs(a.b - b.b) <= tol;
}

PlotSpec sine_plot() {
  PlotSpec p;
  p.width = 800, p.height = 500;
  p.title = "sine";
  p.x_label = "time", p.x_unit = "s";
  p.y_label = "value", p.y_unit = "MPa";
  p.x_range = AxisRange{0, 1};
  p.y_range = AxisRange{-1.5, 1.5};
  p.legend = LegendPosition::None;
  Series s;
  s.name = "sin";
  s.color = Rgb{0, 0, 255};
  s.width = 2;
  for (int i = 0; i <= 2000; ++i) {
    const double x = i / 2000.0;
    s.x.push_back(x);
    s.y.push_back(std::sin(2 * dda::kPi * x));
  }
  p.series.push_back(s);
  return p;
}

}  // namespace

TEST(Plot, SinePeakAndTroughAtTheExpectedRows) {
  const Plot plot = render_plot(sine_plot());
  const PlotLayout& L = plot.layout;
  const Rgb blue{0, 0, 255};
  // Find the topmost and bottommost rows with (nearly) full line colour.
  int top = -1, bottom = -1;
  double top_x = 0;
  int top_n = 0;
  for (int y = L.area.y; y < L.area.bottom(); ++y)
    for (int x = L.area.x; x < L.area.right(); ++x)
      if (near_color(plot.image.pixel(x, y), blue, 40)) {
        if (top < 0 || y == top) top = y, top_x += x + 0.5, ++top_n;
        bottom = y;
      }
  ASSERT_GE(top, 0) << "the curve was not drawn";
  // y = 1 maps to row L.to_py(1) (continuous); a 2 px line covers ±1 px around it.
  const double peak = L.to_py(1.0), trough = L.to_py(-1.0);
  EXPECT_NEAR(peak, L.area.y + 0.5 / 3.0 * L.area.h, 1e-9);  // 1.5 - 1 = a sixth of 3 below the top
  EXPECT_NEAR(top, peak - 1, 1.0);
  EXPECT_NEAR(bottom, trough, 1.0);
  EXPECT_NEAR(top_x / top_n, L.to_px(0.25), 2.0) << "peak at x = 0.25";
}

TEST(Plot, SeveralSeriesWithLegendAndAutomaticRanges) {
  PlotSpec p;
  p.title = "σxx at the bar centre";
  p.x_label = "time", p.x_unit = "s";
  p.y_label = "σxx", p.y_unit = "MPa";
  p.y_scale = 1e-6;
  const double g0[] = {1e9, 5e9, 1e10, 5e10, 1e11};
  for (int k = 0; k < 5; ++k) {
    Series s;
    s.name = "g0 = " + format_number(g0[k], 2) + " N/m";
    for (int i = 0; i <= 400; ++i) {
      const double t = i * 5e-6;
      s.x.push_back(t);
      s.y.push_back(-2e6 * std::sin(2 * dda::kPi * t / 1e-3) * std::exp(-t * (200 + 150 * k)) * (1 + 0.05 * k));
    }
    p.series.push_back(s);
  }
  double lo = 0, hi = 0;
  for (const Series& s : p.series)
    for (double v : s.y) lo = std::min(lo, v * 1e-6), hi = std::max(hi, v * 1e-6);
  const Plot plot = render_plot(p);
  // The automatic range covers the data (in MPa) and is not much wider.
  EXPECT_LE(plot.layout.y.min, lo);
  EXPECT_GE(plot.layout.y.max, hi);
  EXPECT_GT(plot.layout.y.min, lo - 0.5 * (hi - lo));
  EXPECT_LT(plot.layout.y.max, hi + 0.5 * (hi - lo));
  EXPECT_LE(plot.layout.x.min, 0.0);
  EXPECT_GE(plot.layout.x.max, 2e-3);
  EXPECT_LT(plot.layout.x.max, 3e-3);
  ASSERT_FALSE(plot.layout.legend.empty());
  // Every series colour appears in the legend box.
  for (int k = 0; k < 5; ++k) {
    bool found = false;
    const PixelRect& lg = plot.layout.legend;
    for (int y = lg.y; y < lg.bottom() && !found; ++y)
      for (int x = lg.x; x < lg.right() && !found; ++x) found = near_color(plot.image.pixel(x, y), series_color(k), 10);
    EXPECT_TRUE(found) << "series " << k;
  }
  const auto dir = std::filesystem::temp_directory_path() / ("dda_render_plot_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  write_plot_png(p, dir / "fig.png");
  EXPECT_TRUE(std::filesystem::exists(dir / "fig.png"));
  write_plot_png(sine_plot(), dir / "sine.png");
  if (!std::getenv("DDA_RENDER_KEEP")) std::filesystem::remove_all(dir);
}

TEST(Plot, GapsAndEmptyPlots) {
  PlotSpec p = sine_plot();
  p.series[0].y[500] = std::nan("");  // the peak point: a gap in the line
  EXPECT_NO_THROW(render_plot(p));
  PlotSpec empty;
  EXPECT_NO_THROW(render_plot(empty));
}

TEST(Plot, BadSpecsAreClearErrors) {
  PlotSpec p = sine_plot();
  p.series[0].y.pop_back();
  try {
    render_plot(p);
    FAIL() << "no error";
  } catch (const dda::Error& e) {
    EXPECT_NE(std::string(e.what()).find("'sin'"), std::string::npos) << e.what();
  }
  p = sine_plot();
  p.y_range = AxisRange{1, -1};
  EXPECT_THROW(render_plot(p), dda::Error);
  p = sine_plot();
  p.width = 10;
  EXPECT_THROW(render_plot(p), dda::Error);
}

TEST(Ticks, NiceStepsAndMultipliers) {
  Ticks t = nice_ticks(0, 1, 5);
  EXPECT_EQ(t.labels, (std::vector<std::string>{"0.0", "0.2", "0.4", "0.6", "0.8", "1.0"}));
  EXPECT_TRUE(t.multiplier.empty());
  t = nice_ticks(-6.5, 6.5, 6);
  EXPECT_EQ(t.labels.front(), "-6");
  EXPECT_EQ(t.labels.back(), "6");
  t = nice_ticks(0, 3e-5, 3);
  EXPECT_EQ(t.multiplier, "×1e-5");
  EXPECT_EQ(t.labels.back(), "3");
  double lo = -0.93, hi = 2.1;
  nice_range(lo, hi, 6);
  EXPECT_DOUBLE_EQ(lo, -1.0);
  EXPECT_DOUBLE_EQ(hi, 2.5);
}
