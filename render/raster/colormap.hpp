// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Colour maps: viridis (perceptually uniform, for magnitudes) and Moreland's
// cool-warm (diverging, for signed fields). Each is a 256-entry table; a value
// t in [0, 1] picks entry round(255·t), so the same t always gives the same
// colour, in the frame, on the colour bar and in tests.
#include <string_view>

#include "raster/image.hpp"

namespace dda::render {

enum class ColorMap {
  Viridis,   // dark purple (0) → yellow (1)
  CoolWarm,  // blue (0) → light grey (0.5) → red (1)
};

// Colour for t in [0, 1]; t is clamped; a non-finite t gives kInvalidColor.
Rgb color_at(ColorMap map, double t);

// Shown for a block whose value is NaN or infinite.
inline constexpr Rgb kInvalidColor{128, 128, 128};

const char* to_string(ColorMap map);             // "viridis", "coolwarm"
ColorMap parse_colormap(std::string_view name);  // also accepts "diverging"; dda::Error otherwise

}  // namespace dda::render
