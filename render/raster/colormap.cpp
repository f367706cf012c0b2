// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "raster/colormap.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/error.hpp"
#include "core/types.hpp"

namespace dda::render {
namespace {

// viridis, 256 entries, rounded to 8 bits. From matplotlib's _cm_listed.py
// (mpl-colormaps by Nathaniel J. Smith, Stefan van der Walt and Eric Firing),
// released under CC0 / public domain.
constexpr std::uint8_t kViridis[256][3] = {
    {68, 1, 84},    {68, 2, 86},    {69, 4, 87},    {69, 5, 89},    {70, 7, 90},    {70, 8, 92},    {70, 10, 93},
    {70, 11, 94},   {71, 13, 96},   {71, 14, 97},   {71, 16, 99},   {71, 17, 100},  {71, 19, 101},  {72, 20, 103},
    {72, 22, 104},  {72, 23, 105},  {72, 24, 106},  {72, 26, 108},  {72, 27, 109},  {72, 28, 110},  {72, 29, 111},
    {72, 31, 112},  {72, 32, 113},  {72, 33, 115},  {72, 35, 116},  {72, 36, 117},  {72, 37, 118},  {72, 38, 119},
    {72, 40, 120},  {72, 41, 121},  {71, 42, 122},  {71, 44, 122},  {71, 45, 123},  {71, 46, 124},  {71, 47, 125},
    {70, 48, 126},  {70, 50, 126},  {70, 51, 127},  {70, 52, 128},  {69, 53, 129},  {69, 55, 129},  {69, 56, 130},
    {68, 57, 131},  {68, 58, 131},  {68, 59, 132},  {67, 61, 132},  {67, 62, 133},  {66, 63, 133},  {66, 64, 134},
    {66, 65, 134},  {65, 66, 135},  {65, 68, 135},  {64, 69, 136},  {64, 70, 136},  {63, 71, 136},  {63, 72, 137},
    {62, 73, 137},  {62, 74, 137},  {62, 76, 138},  {61, 77, 138},  {61, 78, 138},  {60, 79, 138},  {60, 80, 139},
    {59, 81, 139},  {59, 82, 139},  {58, 83, 139},  {58, 84, 140},  {57, 85, 140},  {57, 86, 140},  {56, 88, 140},
    {56, 89, 140},  {55, 90, 140},  {55, 91, 141},  {54, 92, 141},  {54, 93, 141},  {53, 94, 141},  {53, 95, 141},
    {52, 96, 141},  {52, 97, 141},  {51, 98, 141},  {51, 99, 141},  {50, 100, 142}, {50, 101, 142}, {49, 102, 142},
    {49, 103, 142}, {49, 104, 142}, {48, 105, 142}, {48, 106, 142}, {47, 107, 142}, {47, 108, 142}, {46, 109, 142},
    {46, 110, 142}, {46, 111, 142}, {45, 112, 142}, {45, 113, 142}, {44, 113, 142}, {44, 114, 142}, {44, 115, 142},
    {43, 116, 142}, {43, 117, 142}, {42, 118, 142}, {42, 119, 142}, {42, 120, 142}, {41, 121, 142}, {41, 122, 142},
    {41, 123, 142}, {40, 124, 142}, {40, 125, 142}, {39, 126, 142}, {39, 127, 142}, {39, 128, 142}, {38, 129, 142},
    {38, 130, 142}, {38, 130, 142}, {37, 131, 142}, {37, 132, 142}, {37, 133, 142}, {36, 134, 142}, {36, 135, 142},
    {35, 136, 142}, {35, 137, 142}, {35, 138, 141}, {34, 139, 141}, {34, 140, 141}, {34, 141, 141}, {33, 142, 141},
    {33, 143, 141}, {33, 144, 141}, {33, 145, 140}, {32, 146, 140}, {32, 146, 140}, {32, 147, 140}, {31, 148, 140},
    {31, 149, 139}, {31, 150, 139}, {31, 151, 139}, {31, 152, 139}, {31, 153, 138}, {31, 154, 138}, {30, 155, 138},
    {30, 156, 137}, {30, 157, 137}, {31, 158, 137}, {31, 159, 136}, {31, 160, 136}, {31, 161, 136}, {31, 161, 135},
    {31, 162, 135}, {32, 163, 134}, {32, 164, 134}, {33, 165, 133}, {33, 166, 133}, {34, 167, 133}, {34, 168, 132},
    {35, 169, 131}, {36, 170, 131}, {37, 171, 130}, {37, 172, 130}, {38, 173, 129}, {39, 173, 129}, {40, 174, 128},
    {41, 175, 127}, {42, 176, 127}, {44, 177, 126}, {45, 178, 125}, {46, 179, 124}, {47, 180, 124}, {49, 181, 123},
    {50, 182, 122}, {52, 182, 121}, {53, 183, 121}, {55, 184, 120}, {56, 185, 119}, {58, 186, 118}, {59, 187, 117},
    {61, 188, 116}, {63, 188, 115}, {64, 189, 114}, {66, 190, 113}, {68, 191, 112}, {70, 192, 111}, {72, 193, 110},
    {74, 193, 109}, {76, 194, 108}, {78, 195, 107}, {80, 196, 106}, {82, 197, 105}, {84, 197, 104}, {86, 198, 103},
    {88, 199, 101}, {90, 200, 100}, {92, 200, 99},  {94, 201, 98},  {96, 202, 96},  {99, 203, 95},  {101, 203, 94},
    {103, 204, 92}, {105, 205, 91}, {108, 205, 90}, {110, 206, 88}, {112, 207, 87}, {115, 208, 86}, {117, 208, 84},
    {119, 209, 83}, {122, 209, 81}, {124, 210, 80}, {127, 211, 78}, {129, 211, 77}, {132, 212, 75}, {134, 213, 73},
    {137, 213, 72}, {139, 214, 70}, {142, 214, 69}, {144, 215, 67}, {147, 215, 65}, {149, 216, 64}, {152, 216, 62},
    {155, 217, 60}, {157, 217, 59}, {160, 218, 57}, {162, 218, 55}, {165, 219, 54}, {168, 219, 52}, {170, 220, 50},
    {173, 220, 48}, {176, 221, 47}, {178, 221, 45}, {181, 222, 43}, {184, 222, 41}, {186, 222, 40}, {189, 223, 38},
    {192, 223, 37}, {194, 223, 35}, {197, 224, 33}, {200, 224, 32}, {202, 225, 31}, {205, 225, 29}, {208, 225, 28},
    {210, 226, 27}, {213, 226, 26}, {216, 226, 25}, {218, 227, 25}, {221, 227, 24}, {223, 227, 24}, {226, 228, 24},
    {229, 228, 25}, {231, 228, 25}, {234, 229, 26}, {236, 229, 27}, {239, 229, 28}, {241, 229, 29}, {244, 230, 30},
    {246, 230, 32}, {248, 230, 33}, {251, 231, 35}, {253, 231, 37},
};

// Moreland's smooth diverging map ("Diverging Color Maps for Scientific
// Visualization", K. Moreland, ISVC 2009): interpolate between the end colours
// in the Msh space (polar CIELAB), through an unsaturated white-ish middle.
// Computed once into a table (end points (59,76,192) and (180,4,38), the
// values ParaView uses).
struct Msh {
  double m, s, h;
};

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double linear_to_srgb(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055; }

constexpr double kWhite[3] = {0.95047, 1.0, 1.08883};  // D65

double lab_f(double t) { return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0; }
double lab_finv(double t) { return t > 0.206893 ? t * t * t : (t - 16.0 / 116.0) / 7.787; }

Msh rgb_to_msh(double r8, double g8, double b8) {
  const double r = srgb_to_linear(r8 / 255), g = srgb_to_linear(g8 / 255), b = srgb_to_linear(b8 / 255);
  const double x = 0.4124 * r + 0.3576 * g + 0.1805 * b;
  const double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  const double z = 0.0193 * r + 0.1192 * g + 0.9505 * b;
  const double fx = lab_f(x / kWhite[0]), fy = lab_f(y / kWhite[1]), fz = lab_f(z / kWhite[2]);
  const double L = 116 * fy - 16, A = 500 * (fx - fy), B = 200 * (fy - fz);
  const double m = std::sqrt(L * L + A * A + B * B);
  return {m, std::acos(L / m), std::atan2(B, A)};
}

std::array<std::uint8_t, 3> msh_to_rgb(const Msh& c) {
  const double L = c.m * std::cos(c.s), A = c.m * std::sin(c.s) * std::cos(c.h),
               B = c.m * std::sin(c.s) * std::sin(c.h);
  const double fy = (L + 16) / 116, fx = fy + A / 500, fz = fy - B / 200;
  const double x = kWhite[0] * lab_finv(fx), y = kWhite[1] * lab_finv(fy), z = kWhite[2] * lab_finv(fz);
  const double lin[3] = {3.2406 * x - 1.5372 * y - 0.4986 * z, -0.9689 * x + 1.8758 * y + 0.0415 * z,
                         0.0557 * x - 0.2040 * y + 1.0570 * z};
  std::array<std::uint8_t, 3> out{};
  for (int i = 0; i < 3; ++i) {
    const double v = std::clamp(linear_to_srgb(std::clamp(lin[i], 0.0, 1.0)), 0.0, 1.0);
    out[i] = static_cast<std::uint8_t>(std::lround(v * 255));
  }
  return out;
}

double adjust_hue(const Msh& c, double m_unsat) {
  if (c.m >= m_unsat) return c.h;
  const double spin = c.s * std::sqrt(m_unsat * m_unsat - c.m * c.m) / (c.m * std::sin(c.s));
  return c.h > -kPi / 3 ? c.h + spin : c.h - spin;
}

std::array<std::uint8_t, 3> moreland(double t) {
  Msh a = rgb_to_msh(59, 76, 192), b = rgb_to_msh(180, 4, 38);
  if (a.s > 0.05 && b.s > 0.05 && std::abs(a.h - b.h) > kPi / 3) {
    const double mid = std::max({a.m, b.m, 88.0});
    if (t < 0.5) {
      b = {mid, 0, 0};
      t *= 2;
    } else {
      a = {mid, 0, 0};
      t = 2 * t - 1;
    }
  }
  if (a.s < 0.05 && b.s > 0.05)
    a.h = adjust_hue(b, a.m);
  else if (b.s < 0.05 && a.s > 0.05)
    b.h = adjust_hue(a, b.m);
  return msh_to_rgb({(1 - t) * a.m + t * b.m, (1 - t) * a.s + t * b.s, (1 - t) * a.h + t * b.h});
}

const std::array<Rgb, 256>& coolwarm_table() {
  static const std::array<Rgb, 256> table = [] {
    std::array<Rgb, 256> out{};
    for (int i = 0; i < 256; ++i) {
      const auto c = moreland(i / 255.0);
      out[i] = {c[0], c[1], c[2]};
    }
    return out;
  }();
  return table;
}

}  // namespace

Rgb color_at(ColorMap map, double t) {
  if (!std::isfinite(t)) return kInvalidColor;
  const int i = static_cast<int>(std::lround(std::clamp(t, 0.0, 1.0) * 255));
  switch (map) {
    case ColorMap::Viridis:
      return {kViridis[i][0], kViridis[i][1], kViridis[i][2]};
    case ColorMap::CoolWarm:
      return coolwarm_table()[i];
  }
  return kInvalidColor;
}

const char* to_string(ColorMap map) {
  switch (map) {
    case ColorMap::Viridis:
      return "viridis";
    case ColorMap::CoolWarm:
      return "coolwarm";
  }
  return "?";
}

ColorMap parse_colormap(std::string_view name) {
  if (name == "viridis") return ColorMap::Viridis;
  if (name == "coolwarm" || name == "diverging") return ColorMap::CoolWarm;
  throw Error(msg("unknown colour map '", name, "' (use 'viridis' or 'coolwarm')"));
}

}  // namespace dda::render
