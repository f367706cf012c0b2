// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "contact/contact_detection.hpp"

#include <algorithm>
#include <cmath>

#include "contact/broad_phase.hpp"
#include "contact/mesh_contacts.hpp"
#include "contact/narrow_phase.hpp"
#include "core/load_check.hpp"
#include "core/parallel.hpp"

namespace dda {

namespace {
constexpr double kSearchFactor = 2.0;
constexpr double kRedetectRotation = 0.005;  // rad, well inside the facing-edge angle tolerance
}  // namespace

void ContactDetection::start_automatic_range(const Blocks& blocks) {
  std::vector<double> edges;
  edges.reserve(blocks.vertices.size());
  for (std::size_t b = 0; b < blocks.count(); ++b)
    for (int v = blocks.vertex_start[b]; v < blocks.vertex_start[b + 1]; ++v) {
      const int next = v + 1 < blocks.vertex_start[b + 1] ? v + 1 : blocks.vertex_start[b];
      edges.push_back((blocks.vertices[next] - blocks.vertices[v]).norm());
    }
  std::nth_element(edges.begin(), edges.begin() + edges.size() / 2, edges.end());
  auto_range_ = 0.1 * edges[edges.size() / 2];
}

void ContactDetection::widen_automatic_range(double largest_displacement) {
  auto_range_ = std::max(2.0 * auto_range_, 2.5 * 1.5 * largest_displacement);
}

bool ContactDetection::follow_motion(const Blocks& blocks, const BlockPolygons& polys, double range) {
  const bool reshaped = watch_.start_over_if_reshaped(polys);
  const bool searched_here = detected_vertices_.size() == blocks.vertices.size();
  const double allowed = 0.5 * (kSearchFactor - 1.0) * range;
  const bool moved_far =
      parallel_max<int>(blocks.count(), 0, [&](std::size_t b) {
        if (!reshaped) watch_.follow_block(polys, b);
        if (!searched_here) return 0;
        double moved = 0;  // the largest squared vertex motion since the search
        for (int v = blocks.vertex_start[b]; v < blocks.vertex_start[b + 1]; ++v)
          moved = std::max(moved, (blocks.vertices[v] - detected_vertices_[v]).squaredNorm());
        return moved > allowed * allowed || std::abs(rotation_since_detection_[b]) > kRedetectRotation ? 1 : 0;
      }) != 0;
  return !searched_here || moved_far || detected_range_ != range;
}

bool ContactDetection::detect(const Blocks& blocks, double range, std::vector<Contact>& contacts,
                              ContactLinearisation& lin, std::vector<int>& previous) {
  const BlockPolygons polys = blocks.polygons();
  // Contact i's linearisation, into its two arrays (sized by the caller).
  auto linearise = [&](std::size_t i, const Contact& c) -> const ContactOffsets& {
    const ContactKinematics k = contact_kinematics(polys, blocks.centroid, c);
    lin.gradients[i] = k;
    return lin.offsets[i] = k;
  };
  // A vertex gone round the corner of its contact's edge, or slid past its
  // end, is searched again: it belongs to the next edge there or to a
  // vertex-vertex contact (docs/contact_transfer.md). So are
  // aligned edges slid past each other's corner: their contacts are missing
  // or too weak (narrow_phase.hpp). The watch tests only what can have
  // changed since its last test (transfer_watch.hpp). (After a search the
  // watch starts over: a stale list skips its tests.)
  if (!follow_motion(blocks, polys, range) && !watch_.aligned_slid(polys, aligned_)) {
    // Same contacts unless a vertex left its edge: refresh their
    // linearisation from the current geometry, and test them, in one pass
    // (the refresh is lost only when the list is searched again).
    lin.gradients.resize(contacts.size());
    lin.offsets.resize(contacts.size());
    watch_.watch_contacts(contacts);
    const bool left_an_edge = parallel_max<int>(contacts.size(), 0, [&](std::size_t i) {
                                contacts[i].penetration = linearise(i, contacts[i]).d0;
                                return watch_.left_its_edge(polys, contacts[i], i) ? 1 : 0;
                              }) != 0;
    if (!left_an_edge) return false;
  }
  NarrowPhaseSettings settings;
  settings.range = kSearchFactor * range;
  auto pairs = find_candidate_pairs(polys, settings.range);
  drop_pairs_inside_meshes(blocks, pairs);
  std::vector<Contact> found = detect_contacts(polys, blocks.edge_joint, pairs, settings, &aligned_);
  watch_.forget();
  drop_contacts_inside_meshes(blocks, found);
  detected_vertices_ = blocks.vertices;
  rotation_since_detection_.assign(blocks.count(), 0.0);
  detected_range_ = range;

  // Carry each contact's state over from the previous step (same vertex and
  // edge); new contacts start locked when touching, open otherwise.
  std::vector<int> order(contacts.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int x, int y) { return identity_less(contacts[x], contacts[y]); });
  lin.gradients.resize(found.size());
  lin.offsets.resize(found.size());
  previous.resize(found.size());
  parallel_for_each(found.size(), [&](std::size_t i) {
    Contact& c = found[i];
    const auto it = std::lower_bound(order.begin(), order.end(), c,
                                     [&](int x, const Contact& key) { return identity_less(contacts[x], key); });
    const bool known = it != order.end() && same_identity(contacts[*it], c);
    if (known) {
      set_iteration_state(c, iteration_state(contacts[*it]));  // (penetration: set below)
      c.bonded = contacts[*it].bonded;
    }
    previous[i] = known ? *it : -1;
    const ContactOffsets& k = linearise(i, c);
    if (!known) {
      const bool touching = k.d0 >= -1e-9 * k.edge_length;
      c.state = touching ? ContactState::Locked : ContactState::Open;
      c.intact = c.bonded = touching && first_detection_;
    }
    c.penetration = k.d0;
  });
  contacts = std::move(found);
  first_detection_ = false;
  return true;
}

void ContactDetection::check_loaded(const LoadCheck& check, const Blocks& blocks) const {
  check.require(
      std::isfinite(auto_range_) && auto_range_ >= 0 && std::isfinite(detected_range_) && detected_range_ >= 0,
      "its contact range is ", auto_range_, " (searched with ", detected_range_, ")");
  check.all_finite(detected_vertices_, "searched vertex");
  // follow_motion reads the rotations when the vertices match the blocks'.
  if (detected_vertices_.size() == blocks.vertices.size())
    check.size(rotation_since_detection_.size(), blocks.count(), "blocks", "the rotations since the search");
  check.all_finite(rotation_since_detection_, "rotation since the search of block");
  for (std::size_t i = 0; i < aligned_.size(); ++i) {
    const AlignedEdges& e = aligned_[i];
    check.index(e.a, blocks.count(), "blocks", "aligned edges ", i, "'s first block");
    check.index(e.b, blocks.count(), "blocks", "aligned edges ", i, "'s second block");
    check.index(e.edge_a, static_cast<std::size_t>(blocks.vertex_count(e.a)), "edges", "aligned edges ", i,
                "'s first edge");
    check.index(e.edge_b, static_cast<std::size_t>(blocks.vertex_count(e.b)), "edges", "aligned edges ", i,
                "'s second edge");
    check.finite(e.overlap, "aligned edges ", i, "'s overlap");
  }
}

}  // namespace dda
