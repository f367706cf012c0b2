// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "contact/transfer_watch.hpp"

#include <algorithm>
#include <cmath>

#include "core/parallel.hpp"

namespace dda {

void TransferWatch::follow(const BlockPolygons& blocks) {
  if (start_over_if_reshaped(blocks)) return;
  parallel_for_each(
      blocks.count(), [&](std::size_t b) { follow_block(blocks, b); }, 256);
}

bool TransferWatch::start_over_if_reshaped(const BlockPolygons& blocks) {
  if (std::equal(start_.begin(), start_.end(), blocks.start.begin(), blocks.start.end())) return false;
  start_.assign(blocks.start.begin(), blocks.start.end());
  vertices_.assign(blocks.vertices.begin(), blocks.vertices.end());
  moved_.assign(blocks.count(), 0.0);
  forget();
  return true;
}

void TransferWatch::follow_block(const BlockPolygons& blocks, std::size_t b) {
  double largest = 0;
  for (int v = start_[b]; v < start_[b + 1]; ++v) {
    largest = std::max(largest, (blocks.vertices[v] - vertices_[v]).squaredNorm());
    vertices_[v] = blocks.vertices[v];
  }
  moved_[b] += std::sqrt(largest);
}

template <class Item, class Test>
void TransferWatch::size_slacks(std::span<const Item> items, std::vector<Slack>& slacks, Test test) const {
  if (slacks.size() == items.size()) return;
  const int count = static_cast<int>(moved_.size());
  slacks.resize(items.size());
  for (std::size_t i = 0; i < items.size(); ++i) {
    const auto [a, b] = test.blocks(items[i]);
    // Test now (moved_ is never negative); always, where a block is gone.
    slacks[i] = a < count && b < count ? Slack{a, b, -1.0} : Slack{-1, -1, 0.0};
  }
}

template <class Item, class Test, class SlackOf>
bool TransferWatch::check_one(const BlockPolygons& blocks, const Item& item, Slack& s, Test test,
                              SlackOf slack_of) const {
  const double moved = s.a >= 0 ? moved_[s.a] + moved_[s.b] : 0.0;
  if (moved < s.until) return false;
  if (test(blocks, item)) return true;
  if (s.a >= 0) s.until = moved + slack_of(blocks, item);
  return false;
}

template <class Item, class Test, class SlackOf>
bool TransferWatch::check(const BlockPolygons& blocks, std::span<const Item> items, std::vector<Slack>& slacks,
                          Test test, SlackOf slack_of) {
  size_slacks(items, slacks, test);
  return parallel_max<int>(items.size(), 0, [&](std::size_t i) {
           return check_one(blocks, items[i], slacks[i], test, slack_of) ? 1 : 0;
         }) != 0;
}

namespace {
struct LeftAnEdge {
  std::pair<int, int> blocks(const Contact& c) const { return {c.vblock, c.eblock}; }
  bool operator()(const BlockPolygons& p, const Contact& c) const { return passed_corner(p, c) || slid_past_end(p, c); }
};
struct AlignedSlid {
  std::pair<int, int> blocks(const AlignedEdges& e) const { return {e.a, e.b}; }
  bool operator()(const BlockPolygons& p, const AlignedEdges& e) const { return aligned_edges_slid(p, e); }
};
}  // namespace

bool TransferWatch::left_an_edge(const BlockPolygons& blocks, std::span<const Contact> contacts) {
  return check(blocks, contacts, contacts_, LeftAnEdge{}, transfer_slack);
}

void TransferWatch::watch_contacts(std::span<const Contact> contacts) {
  size_slacks(contacts, contacts_, LeftAnEdge{});
}

bool TransferWatch::left_its_edge(const BlockPolygons& blocks, const Contact& c, std::size_t i) {
  return check_one(blocks, c, contacts_[i], LeftAnEdge{}, transfer_slack);
}

bool TransferWatch::aligned_slid(const BlockPolygons& blocks, std::span<const AlignedEdges> aligned) {
  return check(blocks, aligned, aligned_, AlignedSlid{}, aligned_slack);
}

}  // namespace dda
