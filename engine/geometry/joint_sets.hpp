// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Joint sets turned into segments: the persistent or non-persistent joints of
// one set that can reach a box (the domain's bounding box).
#include <vector>

#include "core/types.hpp"
#include "geometry/cutting.hpp"

namespace dda::geometry {

struct JointSegment {
  Vec2 a, b;
};

// Unit vector of a joint dipping `dip_deg` degrees counter-clockwise from +x.
// Multiples of 90° are exact, so horizontal and vertical joints stay exactly
// horizontal and vertical.
Vec2 dip_direction(double dip_deg);

// Throws dda::Error naming "joint set <index + 1>" for non-finite or
// out-of-range fields, or when the set would make more joints than any model
// could use inside a box of size `box_size` (a spacing far too small).
void validate_joint_set(const JointSet& set, int index, double box_size);

// The joints of `set` that can reach the box [lo, hi]. Persistent joints are
// clipped to the box widened by `margin` on every side, so they cross the
// domain boundary cleanly; non-persistent traces are clipped to the same box.
// `set_index` separates the random streams of sets that share a seed.
// Reproducible: the same set, index and box give the same segments.
std::vector<JointSegment> joint_set_segments(const JointSet& set, int set_index, const Vec2& lo, const Vec2& hi,
                                             double margin);

}  // namespace dda::geometry
