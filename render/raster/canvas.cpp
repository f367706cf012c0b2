// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "raster/canvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace dda::render {

void stroke_polyline(Image& image, const std::vector<PointF>& points, double width, Rgb color,
                     const PixelRect& clip_in) {
  PixelRect clip = clip_in;
  clip.x = std::max(clip.x, 0), clip.y = std::max(clip.y, 0);
  clip.w = std::min(clip_in.right(), image.width()) - clip.x;
  clip.h = std::min(clip_in.bottom(), image.height()) - clip.y;
  if (clip.empty() || points.size() < 2 || !(width > 0)) return;

  // Coverage of each pixel is the max over segments (not the sum), so joints
  // and self-crossings blend once. Only the touched rows/columns are kept.
  std::vector<float> cover(static_cast<std::size_t>(clip.w) * clip.h, 0.0f);
  int bx0 = clip.right(), by0 = clip.bottom(), bx1 = clip.x - 1, by1 = clip.y - 1;
  const double r = width / 2;

  auto segment = [&](PointF a, PointF b) {
    // Long segments are cut into short pieces so each piece's bounding box is small.
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    const int pieces = std::max(1, static_cast<int>(std::ceil(len / 8)));
    for (int p = 0; p < pieces; ++p) {
      const PointF p0{a.x + (b.x - a.x) * p / pieces, a.y + (b.y - a.y) * p / pieces};
      const PointF p1{a.x + (b.x - a.x) * (p + 1) / pieces, a.y + (b.y - a.y) * (p + 1) / pieces};
      const int x0 = std::max(clip.x, static_cast<int>(std::floor(std::min(p0.x, p1.x) - r - 1)));
      const int x1 = std::min(clip.right() - 1, static_cast<int>(std::ceil(std::max(p0.x, p1.x) + r + 1)));
      const int y0 = std::max(clip.y, static_cast<int>(std::floor(std::min(p0.y, p1.y) - r - 1)));
      const int y1 = std::min(clip.bottom() - 1, static_cast<int>(std::ceil(std::max(p0.y, p1.y) + r + 1)));
      if (x0 > x1 || y0 > y1) continue;
      bx0 = std::min(bx0, x0), bx1 = std::max(bx1, x1), by0 = std::min(by0, y0), by1 = std::max(by1, y1);
      const double dx = p1.x - p0.x, dy = p1.y - p0.y, dd = dx * dx + dy * dy;
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
          const double cx = x + 0.5, cy = y + 0.5;
          double t = dd > 0 ? ((cx - p0.x) * dx + (cy - p0.y) * dy) / dd : 0;
          t = std::clamp(t, 0.0, 1.0);
          const double ex = cx - (p0.x + t * dx), ey = cy - (p0.y + t * dy);
          const double c = std::clamp(r + 0.5 - std::sqrt(ex * ex + ey * ey), 0.0, 1.0);
          float& dst = cover[static_cast<std::size_t>(y - clip.y) * clip.w + (x - clip.x)];
          dst = std::max(dst, static_cast<float>(c));
        }
      }
    }
  };

  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const PointF a = points[i], b = points[i + 1];
    if (!std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(b.x) || !std::isfinite(b.y)) continue;
    segment(a, b);
  }
  for (int y = by0; y <= by1; ++y)
    for (int x = bx0; x <= bx1; ++x)
      if (const float c = cover[static_cast<std::size_t>(y - clip.y) * clip.w + (x - clip.x)]; c > 0)
        image.blend_pixel(x, y, color, c);
}

void outline_rect(Image& image, const PixelRect& r, Rgb color) {
  if (r.empty()) return;
  image.fill_rect({r.x, r.y, r.w, 1}, color);
  image.fill_rect({r.x, r.bottom() - 1, r.w, 1}, color);
  image.fill_rect({r.x, r.y, 1, r.h}, color);
  image.fill_rect({r.right() - 1, r.y, 1, r.h}, color);
}

namespace {

double nice_step(double lo, double hi, int target) {
  const double span = hi - lo;
  if (!(span > 0) || !std::isfinite(span)) return 1;
  const double raw = span / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / mag;
  const double nice = f < 1.5 ? 1 : f < 3 ? 2 : f < 7 ? 5 : 10;
  return nice * mag;
}

}  // namespace

void nice_range(double& lo, double& hi, int target) {
  if (!(hi > lo)) return;
  const double step = nice_step(lo, hi, target);
  lo = std::floor(lo / step + 1e-9) * step;
  hi = std::ceil(hi / step - 1e-9) * step;
}

Ticks nice_ticks(double lo, double hi, int target) {
  Ticks out;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return out;
  const double step = nice_step(lo, hi, target);
  const double maxabs = std::max(std::abs(lo), std::abs(hi));
  // Factor out a power of ten when plain labels would be long.
  int exponent = 0;
  if (maxabs >= 1e5 || maxabs < 1e-3) exponent = static_cast<int>(std::floor(std::log10(maxabs)));
  const double unit = std::pow(10.0, exponent);
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step / unit) + 1e-9)));
  const long first = static_cast<long>(std::ceil(lo / step - 1e-9));
  const long last = static_cast<long>(std::floor(hi / step + 1e-9));
  for (long k = first; k <= last; ++k) {
    const double v = k * step;
    out.values.push_back(v);
    char buf[64];
    double shown = v / unit;
    if (std::abs(shown) < step / unit * 1e-6) shown = 0;  // no "-0.0"
    std::snprintf(buf, sizeof buf, "%.*f", decimals, shown);
    out.labels.emplace_back(buf);
  }
  if (exponent != 0) out.multiplier = "×1e" + std::to_string(exponent);
  return out;
}

std::string format_number(double v, int significant) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", significant, v);
  return buf;
}

}  // namespace dda::render
