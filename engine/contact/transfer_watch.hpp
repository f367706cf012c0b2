// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The contact-transfer checks of a reused contact list, run only where their
// answer can have changed. Each step, every kept contact's vertex must be
// tested for having left its edge (passed_corner, slid_past_end), and every
// watched pair of aligned edges for having slid past a corner
// (aligned_edges_slid; narrow_phase.hpp). Most contacts barely move, so the
// watch keeps, per contact and per aligned pair, how far its two blocks may
// move before the exact test could turn true (transfer_slack,
// aligned_slack), and per block a bound of how far each of its vertices has
// moved (the sum of its largest vertex displacement at each check). A test
// runs again only once its blocks' bounds have used up its slack: a skipped
// test would have answered false, so the answers, and the steps, are those
// of testing everything every step, bit for bit (docs/contact_transfer.md).
#include <algorithm>
#include <span>
#include <vector>

#include "contact/contact.hpp"
#include "contact/narrow_phase.hpp"
#include "geometry/block_polygons.hpp"

namespace dda {

class TransferWatch {
 public:
  // Adds each block's largest vertex displacement since the last call to its
  // bound; blocks whose outlines changed (vertex counts) start the watch over.
  void follow(const BlockPolygons& blocks);
  // follow in two parts, for a caller's own pass over the blocks: whether
  // the outlines changed (then the watch starts over, and there is nothing
  // to follow), else follow_block for every block.
  bool start_over_if_reshaped(const BlockPolygons& blocks);
  void follow_block(const BlockPolygons& blocks, std::size_t b);
  // Whether a contact's vertex has left its edge (passed_corner or
  // slid_past_end), `contacts` being the list that the watch has followed
  // since the last forget().
  bool left_an_edge(const BlockPolygons& blocks, std::span<const Contact> contacts);
  // left_an_edge one contact at a time, for a caller's own pass over the
  // list: watch_contacts before the pass, then left_its_edge for each.
  void watch_contacts(std::span<const Contact> contacts);
  bool left_its_edge(const BlockPolygons& blocks, const Contact& c, std::size_t i);
  // Whether aligned edges slid past each other's corner (aligned_edges_slid),
  // `aligned` being the list followed since the last forget().
  bool aligned_slid(const BlockPolygons& blocks, std::span<const AlignedEdges> aligned);
  // A new contact list (a search, a restored checkpoint): every test runs
  // at the next check. (The bounds start again from 0: they stay small,
  // and their sums exact to far below any slack.)
  void forget() {
    contacts_.clear();
    aligned_.clear();
    std::fill(moved_.begin(), moved_.end(), 0.0);
  }

 private:
  // A test's blocks and the sum of their bounds up to which it answers false.
  struct Slack {
    int a, b;
    double until;
  };
  template <class Item, class Test>
  void size_slacks(std::span<const Item> items, std::vector<Slack>& slacks, Test test) const;
  template <class Item, class Test, class SlackOf>
  bool check_one(const BlockPolygons& blocks, const Item& item, Slack& s, Test test, SlackOf slack_of) const;
  template <class Item, class Test, class SlackOf>
  bool check(const BlockPolygons& blocks, std::span<const Item> items, std::vector<Slack>& slacks, Test test,
             SlackOf slack_of);

  std::vector<int> start_;       // the outlines' vertex ranges at the last call
  std::vector<Vec2> vertices_;   // the vertices at the last call
  std::vector<double> moved_;    // per block: how far any of its vertices can have moved since the start
  std::vector<Slack> contacts_;  // per contact of the list
  std::vector<Slack> aligned_;   // per aligned pair
};

}  // namespace dda
