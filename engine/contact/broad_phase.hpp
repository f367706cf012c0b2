// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Broad phase: the block pairs whose bounding boxes, grown by the contact
// search range, overlap. A uniform grid (cell = largest ordinary block), so
// the cost is O(N) for compact models; the output is sorted, whatever the
// thread count.
#include <utility>
#include <vector>

#include "geometry/block_polygons.hpp"

namespace dda {

// Pairs (i, j) with i < j, sorted.
std::vector<std::pair<int, int>> find_candidate_pairs(const BlockPolygons& blocks, double range);

}  // namespace dda
