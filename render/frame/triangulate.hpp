// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Triangles of a simple polygon, for filling blocks with OpenGL.
#include <array>
#include <span>
#include <vector>

#include "core/types.hpp"

namespace dda::render {

// Appends triangles (as index triples into `polygon`) covering the polygon.
// Convex polygons get a fan; others are cut by ear clipping (O(n²), blocks
// have few vertices). Either orientation is accepted. A polygon that is not
// simple (e.g. a block turned inside out by a large magnification) still gets
// triangles — what is left after the ears run out is fanned — so something
// is always drawn.
void triangulate(std::span<const Vec2> polygon, std::vector<std::array<int, 3>>& out);

}  // namespace dda::render
