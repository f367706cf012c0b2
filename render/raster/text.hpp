// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Text for frames and plots, drawn in software into an Image.
//
// Uses a TrueType font through stb_truetype when one is found (the path in
// $DDA_RENDER_FONT, else DejaVu Sans from Debian's fonts-dejavu-core), and
// falls back to stb_easy_font's built-in bitmap font otherwise (ASCII only:
// Greek letters are spelled with Latin ones, σ → s, τ → t). Set
// DDA_RENDER_FONT=none to force the fallback. Text is UTF-8.
#include <string>
#include <string_view>

#include "raster/image.hpp"

namespace dda::render {

enum class Align { Start, Center, End };  // left/top, centre, right/bottom

struct TextStyle {
  float size = 14;  // pixel height of a line (ascent + descent)
  Rgb color{0, 0, 0};
  Align h = Align::Start;
  Align v = Align::Start;
  bool vertical = false;  // rotated 90° anticlockwise: reads bottom to top
};

int text_width(std::string_view utf8, float size);  // advance, in pixels
int text_height(float size);                        // line height, in pixels

// Draws the text's box anchored at (x, y) as the style's alignment says (for
// vertical text, h aligns along x and v along y of the rotated box).
void draw_text(Image& image, int x, int y, std::string_view utf8, const TextStyle& style);

// Which font is in use, for logs: a file path, or "stb_easy_font".
std::string font_description();

}  // namespace dda::render
