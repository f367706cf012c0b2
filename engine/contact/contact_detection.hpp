// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The DetectContacts stage: which vertex-edge pairs are contacts this step,
// with the state each carries over, and their linearisation.
//
// Contacts are searched for over twice the range a step can close, and the
// list is reused until a vertex has moved half the difference, or a block
// turned by kRedetectRotation, since the last search (a Verlet list): no
// contact that can close in the step is missed, and wave problems, whose
// blocks move micrometres, search once. The list is also searched again when
// a contact's vertex has left its edge (contact transfer) and when aligned
// edges that met end to end at the search have slid along their line past
// each other's corner (AlignedEdges, narrow_phase.hpp): the search left them
// without a contact, or with one scaled by their short overlap, and a
// vertex would otherwise sink unresisted into the other block's edge
// (docs/contact_transfer.md); both are tested only where the blocks have moved
// enough to change the answer (transfer_watch.hpp). The linearisation is
// refreshed every step.
#include <span>
#include <vector>

#include "block/blocks.hpp"
#include "contact/contact.hpp"
#include "contact/contact_kinematics.hpp"
#include "contact/narrow_phase.hpp"
#include "contact/transfer_watch.hpp"

namespace dda {

// The contacts' linearisation at the start of the step (contact_kinematics.hpp), in
// two arrays parallel to the contact list.
struct ContactLinearisation {
  std::vector<ContactGradients> gradients;
  std::vector<ContactOffsets> offsets;
};

class ContactDetection {
 public:
  // The automatic range starts at a tenth of the median edge length (fine
  // models then do not carry their blocks' second neighbours as contacts),
  // set again whenever the model's blocks change.
  void start_automatic_range(const Blocks& blocks);
  // The contact range: `fixed` when positive, else the automatic range, at
  // most Shi's 2.5·g2·(half height) (`shi_range`), which the g2 bound on a
  // step's motion already guarantees.
  double range(double fixed, double shi_range) const { return fixed > 0 ? fixed : std::min(shi_range, auto_range_); }
  // Widens the automatic range past a step's largest vertex motion (the step
  // is then redone with the same Δt; the range only widens).
  void widen_automatic_range(double largest_displacement);

  // Searches again when the list is stale (new contacts start locked when
  // touching, open otherwise; intact when touching before the first step;
  // known ones keep their iteration state), then linearises every contact
  // and sets its penetration. Returns whether it searched; if it did,
  // `previous` says where each contact of the new list was in the old one
  // (-1: new), for the contact law's per-contact history.
  bool detect(const Blocks& blocks, double range, std::vector<Contact>& contacts, ContactLinearisation& linearisation,
              std::vector<int>& previous);
  // Block b's rotation in the accepted step (its d[2]), for the redetection
  // rule; called from Update's pass over the blocks (only the blocks the
  // last search saw have a sum).
  void add_rotation(std::size_t b, double rotation) {
    if (b < rotation_since_detection_.size()) rotation_since_detection_[b] += rotation;
  }

  // What a checkpoint holds (core/archive.hpp): the range and what the
  // list's staleness is measured from.
  template <class Archive>
  void fields(Archive& ar) {
    ar(auto_range_, first_detection_, detected_vertices_, rotation_since_detection_, detected_range_, aligned_);
    if constexpr (Archive::reading) watch_.forget();  // (a cache: the next checks are exact)
  }
  // Read from a checkpoint: the watched edges and the lists the staleness
  // test reads sized for the blocks (core/load_check.hpp).
  void check_loaded(const LoadCheck& check, const Blocks& blocks) const;

 private:
  // Follows the blocks' motion for the watch and says whether the list is
  // stale (vertices moved or blocks turned too far since the search, or
  // another range): one pass over the blocks.
  bool follow_motion(const Blocks& blocks, const BlockPolygons& polys, double range);

  double auto_range_ = 0;        // the automatic contact range so far (only widens)
  bool first_detection_ = true;  // contacts found before the first step are intact joints
  std::vector<Vec2> detected_vertices_;
  std::vector<double> rotation_since_detection_;
  double detected_range_ = 0;
  std::vector<AlignedEdges> aligned_;  // aligned edges at the last search, watched for sliding
  TransferWatch watch_;                // when the contact-transfer checks can have changed their answer
};

}  // namespace dda
