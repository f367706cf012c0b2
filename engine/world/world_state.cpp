// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "world/world_state.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace dda {

void WorldState::check_loaded(const LoadCheck& check) const {
  for (std::size_t i = 0; i < rocks.size(); ++i) try {
      validate(rocks[i], static_cast<int>(i));
    } catch (const Error& e) {
      check.fail(e.what());
    }
  for (std::size_t i = 0; i < joints.size(); ++i) try {
      validate(joints[i], static_cast<int>(i));
    } catch (const Error& e) {
      check.fail(e.what());
    }
  blocks.check_loaded(check, rocks.size(), joints.size());
  loads.check_loaded(check, blocks);
  boundaries.check_loaded(check, blocks);
  for (std::size_t i = 0; i < tracked.size(); ++i)
    dda::check_loaded(check, tracked[i], blocks, msg("tracked point ", i));
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    check.index(c.vblock, blocks.count(), "blocks", "contact ", i, "'s vertex block");
    check.index(c.eblock, blocks.count(), "blocks", "contact ", i, "'s edge block");
    check.require(c.vblock != c.eblock, "contact ", i, " joins block ", c.vblock, " to itself");
    check.index(c.vertex, static_cast<std::size_t>(blocks.vertex_count(c.vblock)), "vertices", "contact ", i,
                "'s vertex");
    check.index(c.edge, static_cast<std::size_t>(blocks.vertex_count(c.eblock)), "edges", "contact ", i, "'s edge");
    check.index(c.joint, joints.size(), "joint materials", "contact ", i, "'s joint material");
    check.require(std::isfinite(c.length) && c.length >= 0 && c.scale > 0 && c.scale <= 1, "contact ", i,
                  " has length ", c.length, " and scale ", c.scale);
    check.require(c.slide_sign >= -1 && c.slide_sign <= 1, "contact ", i, "'s slide sign is ", int(c.slide_sign));
    for (const double v : {c.ref_param, c.normal_force, c.shear_force, c.penetration})
      check.require(!std::isnan(v), "contact ", i, " holds NaN");
  }
  check_loaded_wave_model(check);
  check.require(std::isfinite(time) && steps >= 0 && std::isfinite(dt) && dt >= 0 && std::isfinite(half_height) &&
                    half_height >= 0,
                "its clock (t = ", time, ", step ", steps, ", dt = ", dt, ")");
}

// The wave model's figures and the in-place meshing's map: old_vertex_start
// the old blocks' first edge slots (from 0, not decreasing, one past the
// last at the end: as many slots as pieces), each piece an edge of a block
// there is now.
void WorldState::check_loaded_wave_model(const LoadCheck& check) const {
  check.require(std::isfinite(wave.frequency) && wave.frequency >= 0 && std::isfinite(wave.element_size) &&
                    wave.element_size >= 0 && wave.meshed_blocks >= 0,
                "its wave model (frequency ", wave.frequency, ", element size ", wave.element_size, ", ",
                wave.meshed_blocks, " blocks meshed)");
  const std::vector<int>& start = remeshing.old_vertex_start;
  if (start.empty()) {
    check.require(remeshing.pieces.empty() && wave.meshed_blocks == 0, "its meshing map has pieces and no blocks");
    return;
  }
  check.require(start.front() == 0, "its meshing map starts at edge ", start.front());
  for (std::size_t b = 1; b < start.size(); ++b)
    check.require(start[b] >= start[b - 1], "its meshing map goes back at old block ", b);
  check.size(remeshing.pieces.size(), static_cast<std::size_t>(start.back()), "old edges", "its meshing map");
  for (std::size_t i = 0; i < remeshing.pieces.size(); ++i)
    for (const EdgeRef& e : remeshing.pieces[i]) {
      check.index(e.block, blocks.count(), "blocks", "old edge ", i, "'s piece block");
      check.index(e.edge, static_cast<std::size_t>(blocks.vertex_count(e.block)), "edges", "old edge ", i,
                  "'s piece edge");
    }
}

double WorldState::measured_half_height() const {
  double lo = INFINITY, hi = -INFINITY;
  for (const Vec2& v : blocks.vertices) {
    lo = std::min(lo, v.y());
    hi = std::max(hi, v.y());
  }
  return blocks.vertices.empty() ? 0 : 0.5 * (hi - lo);
}

double WorldState::contact_spring() const {
  double e_max = 0;
  for (const RockMaterial& r : rocks) e_max = std::max(e_max, r.youngs);
  return controls.g0 > 0 ? controls.g0 : 50 * e_max;
}

}  // namespace dda
