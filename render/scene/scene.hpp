// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// What a frame shows, as plain data: block outlines and per-block values, plus
// contacts, monitor points, time and step. The renderer draws a Scene; it never
// reads a dda::World directly. `snapshot()` (scene/world_scene.hpp) fills one
// from a World; tests and benchmarks fill one by hand.
//
// Units are SI: m, Pa (tension positive), m/s, s.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "contact/contact.hpp"
#include "core/types.hpp"

namespace dda::render {

struct Box {
  double xmin = 0, ymin = 0, xmax = 0, ymax = 0;
  double width() const { return xmax - xmin; }
  double height() const { return ymax - ymin; }
};

struct ContactMark {
  BlockId block = -1;  // the contact's vertex is vertex `vertex` of block `block`
  std::int32_t vertex = -1;
  ContactState state = ContactState::Open;
  // The edge it touches (edge `edge` of block `eblock`; -1: not known) and
  // whether the joint there has failed: it was bonded when the run began
  // (touching before the first step, on a joint material with cohesion or
  // tensile strength) and has since lost that strength. A cohesionless joint
  // has nothing to lose and a contact made later never was a joint: neither
  // is failed.
  BlockId eblock = -1;
  std::int32_t edge = -1;
  bool failed = false;
};

struct MonitorMark {
  std::string name;
  Vec2 position = Vec2::Zero();      // current position (m)
  Vec2 displacement = Vec2::Zero();  // since the start (m); used when deformation is magnified
};

struct Scene {
  // Block b owns vertices[offsets[b] .. offsets[b+1]): a simple polygon,
  // counter-clockwise, the closing vertex not repeated. offsets has
  // block_count()+1 entries and starts with 0.
  std::vector<std::int32_t> offsets{0};
  std::vector<Vec2> vertices;
  // Where each vertex started (same layout as `vertices`), or empty when not
  // known. Used to magnify the deformation (FrameOptions::magnify); without
  // it only rigid translation is magnified.
  std::vector<Vec2> initial_vertices;

  // Per block.
  std::vector<Vec2> centroids;     // m (current)
  std::vector<Vec3> stress;        // (σxx, σyy, τxy), Pa, tension positive
  std::vector<Vec2> velocity;      // centroid velocity (m/s)
  std::vector<Vec2> displacement;  // centroid displacement since the start (m)

  std::vector<ContactMark> contacts;
  std::vector<MonitorMark> monitors;

  double time = 0;  // simulated time (s)
  long step = 0;    // step count

  std::size_t block_count() const { return centroids.size(); }
  std::span<const Vec2> block_vertices(std::size_t b) const {
    return {vertices.data() + offsets[b], static_cast<std::size_t>(offsets[b + 1] - offsets[b])};
  }

  // Appends a block; its centroid is computed from the outline. `initial`
  // (optional) is the outline at the start, vertex for vertex.
  BlockId add_block(std::span<const Vec2> outline, const Vec3& stress = Vec3::Zero(),
                    const Vec2& velocity = Vec2::Zero(), const Vec2& displacement = Vec2::Zero(),
                    std::span<const Vec2> initial = {});

  // Checks the arrays agree (sizes, offsets, ids of contacts, finite
  // coordinates). Throws dda::Error saying what is wrong.
  void validate() const;

  // Bounding box of the outlines as drawn with deformation magnified by
  // `magnify` (1 = as they are). Empty scene → all zero.
  Box bounds(double magnify = 1) const;

  // Vertex k (of the flat array; it belongs to block b) as drawn with the
  // deformation magnified: initial + magnify·(current − initial). Without
  // initial vertices only the block's centroid displacement is magnified.
  Vec2 drawn_vertex(std::size_t b, std::size_t k, double magnify) const {
    if (magnify == 1) return vertices[k];
    if (initial_vertices.empty()) return vertices[k] + (magnify - 1) * displacement[b];
    return initial_vertices[k] + magnify * (vertices[k] - initial_vertices[k]);
  }
  // Centroid as drawn (moved by the magnified centroid displacement).
  Vec2 drawn_centroid(std::size_t b, double magnify) const {
    return magnify == 1 ? centroids[b] : Vec2(centroids[b] + (magnify - 1) * displacement[b]);
  }
};

// Area-weighted centroid of a simple polygon (the vertex mean if degenerate).
Vec2 polygon_centroid(std::span<const Vec2> outline);

}  // namespace dda::render
