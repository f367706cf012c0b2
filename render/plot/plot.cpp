// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "plot/plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "raster/canvas.hpp"
#include "raster/text.hpp"

namespace dda::render {
namespace {

constexpr Rgb kAxis{30, 30, 30};
constexpr Rgb kGrid{225, 225, 225};
constexpr Rgb kText{20, 20, 20};

// Tableau 10: distinct, and readable by most colour-blind viewers.
constexpr Rgb kPalette[10] = {{31, 119, 180}, {255, 127, 14},  {44, 160, 44},   {214, 39, 40},  {148, 103, 189},
                              {140, 86, 75},  {227, 119, 194}, {127, 127, 127}, {188, 189, 34}, {23, 190, 207}};

std::string axis_title(const std::string& label, const std::string& unit, const std::string& multiplier) {
  std::string u = multiplier.empty() ? unit : unit.empty() ? multiplier : multiplier + " " + unit;
  if (u.empty()) return label;
  return label.empty() ? "(" + u + ")" : label + " (" + u + ")";
}

// Data range of the finite points, in display units.
AxisRange data_range(const PlotSpec& s, bool x_axis) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Series& se : s.series)
    for (std::size_t i = 0; i < se.x.size(); ++i) {
      const double xv = se.x[i] * s.x_scale, yv = se.y[i] * s.y_scale;
      if (!std::isfinite(xv) || !std::isfinite(yv)) continue;
      const double v = x_axis ? xv : yv;
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
  if (!(hi >= lo)) return {0, 1};
  if (hi == lo) {
    const double pad = lo == 0 ? 1 : 0.5 * std::abs(lo);
    return {lo - pad, hi + pad};
  }
  return {lo, hi};
}

}  // namespace

Rgb series_color(std::size_t index) { return kPalette[index % 10]; }

void PlotSpec::validate() const {
  if (width < 64 || height < 64 || width > 8192 || height > 8192)
    throw Error(msg("plot size ", width, "x", height, " is out of range (64 .. 8192 pixels a side)"));
  if (!(std::isfinite(x_scale) && x_scale != 0 && std::isfinite(y_scale) && y_scale != 0))
    throw Error(msg("plot scales (", x_scale, ", ", y_scale, ") must be finite and non-zero"));
  for (std::size_t i = 0; i < series.size(); ++i) {
    if (series[i].x.size() != series[i].y.size())
      throw Error(msg("plot series ", i, " ('", series[i].name, "'): ", series[i].x.size(), " x values but ",
                      series[i].y.size(), " y values"));
    if (!(series[i].width > 0 && series[i].width <= 32))
      throw Error(
          msg("plot series ", i, " ('", series[i].name, "'): line width ", series[i].width, " must be in (0, 32]"));
  }
  for (const auto* r : {&x_range, &y_range})
    if (*r && !(std::isfinite((*r)->min) && std::isfinite((*r)->max) && (*r)->max > (*r)->min))
      throw Error(msg("plot axis range [", (*r)->min, ", ", (*r)->max, "] must be finite with min < max"));
}

Plot render_plot(const PlotSpec& s) {
  s.validate();
  Plot plot;
  PlotLayout& L = plot.layout;
  Image& img = plot.image;
  img = Image(s.width, s.height, s.background);

  const float text = std::clamp(s.height / 38.0f, 10.0f, 28.0f);
  const float title_size = text * 1.25f;
  const int th = text_height(text), m = static_cast<int>(std::lround(text * 0.8));
  const int tick = std::max(4, static_cast<int>(std::lround(text * 0.4)));

  // Ranges first: the tick labels decide the margins.
  if (s.x_range)
    L.x = *s.x_range;
  else {
    L.x = data_range(s, true);
    nice_range(L.x.min, L.x.max, 8);
  }
  if (s.y_range)
    L.y = *s.y_range;
  else {
    L.y = data_range(s, false);
    nice_range(L.y.min, L.y.max, 6);
  }
  const Ticks xt = nice_ticks(L.x.min, L.x.max, std::clamp(s.width / 130, 3, 10));
  const Ticks yt = nice_ticks(L.y.min, L.y.max, std::clamp(s.height / 80, 3, 10));
  int ylab_w = 0;
  for (const std::string& l : yt.labels) ylab_w = std::max(ylab_w, text_width(l, text));

  const int top = m + (s.title.empty() ? 0 : text_height(title_size) + m / 2);
  const int left = m + th + m / 2 + ylab_w + tick + 4;
  const int bottom = m + th + m / 2 + th + tick + 4;
  const int right = m + text_width(xt.labels.empty() ? "" : xt.labels.back(), text) / 2;
  L.area = {left, top, s.width - left - right, s.height - top - bottom};
  if (L.area.w < 16 || L.area.h < 16) throw Error(msg("plot ", s.width, "x", s.height, " is too small for its labels"));
  const PixelRect& A = L.area;

  // Grid, ticks and labels.
  for (std::size_t i = 0; i < xt.values.size(); ++i) {
    const int x = static_cast<int>(std::floor(L.to_px(xt.values[i])));
    if (s.grid) img.fill_rect({x, A.y, 1, A.h}, kGrid);
    img.fill_rect({x, A.bottom(), 1, tick}, kAxis);
    draw_text(img, x, A.bottom() + tick + 2, xt.labels[i], {text, kText, Align::Center});
  }
  for (std::size_t i = 0; i < yt.values.size(); ++i) {
    const int y = static_cast<int>(std::floor(L.to_py(yt.values[i])));
    if (s.grid) img.fill_rect({A.x, y, A.w, 1}, kGrid);
    img.fill_rect({A.x - tick, y, tick, 1}, kAxis);
    draw_text(img, A.x - tick - 3, y, yt.labels[i], {text, kText, Align::End, Align::Center});
  }
  if (!s.title.empty()) draw_text(img, A.x + A.w / 2, m, s.title, {title_size, kText, Align::Center});
  draw_text(img, A.x + A.w / 2, s.height - m, axis_title(s.x_label, s.x_unit, xt.multiplier),
            {text, kText, Align::Center, Align::End});
  draw_text(img, m, A.y + A.h / 2, axis_title(s.y_label, s.y_unit, yt.multiplier),
            {text, kText, Align::Start, Align::Center, true});

  // Series, clipped to the area. Axis values beyond a few areas are clamped
  // so a wild point still draws a steep line instead of overflowing.
  const double xscale = s.x_scale, yscale = s.y_scale;
  std::vector<std::vector<PointF>> drawn(s.series.size());
  for (std::size_t k = 0; k < s.series.size(); ++k) {
    const Series& se = s.series[k];
    std::vector<PointF>& pts = drawn[k];
    pts.resize(se.x.size());
    for (std::size_t i = 0; i < se.x.size(); ++i) {
      const double xv = se.x[i] * xscale, yv = se.y[i] * yscale;
      if (!std::isfinite(xv) || !std::isfinite(yv)) {
        pts[i] = {std::numeric_limits<double>::quiet_NaN(), 0};
        continue;
      }
      pts[i] = {std::clamp(L.to_px(xv), A.x - 4.0 * A.w, A.right() + 4.0 * A.w),
                std::clamp(L.to_py(yv), A.y - 4.0 * A.h, A.bottom() + 4.0 * A.h)};
    }
    stroke_polyline(img, pts, se.width, se.color.value_or(series_color(k)), A);
  }
  outline_rect(img, {A.x - 1, A.y - 1, A.w + 2, A.h + 2}, kAxis);

  // Legend.
  std::vector<std::size_t> named;
  for (std::size_t k = 0; k < s.series.size(); ++k)
    if (!s.series[k].name.empty()) named.push_back(k);
  if (s.legend != LegendPosition::None && !named.empty()) {
    const int swatch = static_cast<int>(std::lround(text * 2)), row = th + 4;
    int name_w = 0;
    for (std::size_t k : named) name_w = std::max(name_w, text_width(s.series[k].name, text));
    const int w = m / 2 + swatch + m / 2 + name_w + m / 2, h = static_cast<int>(named.size()) * row + m / 2;
    auto corner = [&](LegendPosition pos) {
      const bool at_right = pos == LegendPosition::TopRight || pos == LegendPosition::BottomRight;
      const bool at_top = pos == LegendPosition::TopRight || pos == LegendPosition::TopLeft;
      return PixelRect{at_right ? A.right() - m - w : A.x + m, at_top ? A.y + m : A.bottom() - m - h, w, h};
    };
    LegendPosition where = s.legend;
    if (where == LegendPosition::Best) {
      std::size_t best_count = std::numeric_limits<std::size_t>::max();
      for (LegendPosition pos : {LegendPosition::TopRight, LegendPosition::TopLeft, LegendPosition::BottomRight,
                                 LegendPosition::BottomLeft}) {
        const PixelRect r = corner(pos);
        std::size_t count = 0;
        for (const auto& pts : drawn)
          for (const PointF& q : pts)
            if (std::isfinite(q.x) && r.contains(static_cast<int>(std::floor(q.x)), static_cast<int>(std::floor(q.y))))
              ++count;
        if (count < best_count) best_count = count, where = pos;
      }
    }
    L.legend = corner(where);
    img.fill_rect(L.legend, {255, 255, 255});
    outline_rect(img, L.legend, {160, 160, 160});
    for (std::size_t i = 0; i < named.size(); ++i) {
      const Series& se = s.series[named[i]];
      const int y = L.legend.y + m / 4 + static_cast<int>(i) * row;
      const double cy = y + row / 2.0;
      stroke_line(img, {L.legend.x + m / 2.0, cy}, {L.legend.x + m / 2.0 + swatch, cy}, se.width,
                  se.color.value_or(series_color(named[i])), L.legend);
      draw_text(img, L.legend.x + m + swatch, static_cast<int>(cy), se.name,
                {text, kText, Align::Start, Align::Center});
    }
  }
  return plot;
}

void write_plot_png(const PlotSpec& spec, const std::filesystem::path& path) {
  write_png(render_plot(spec).image, path);
}

}  // namespace dda::render
