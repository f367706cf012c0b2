// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Narrow phase: the vertex-edge contacts of each candidate block pair.
//
// Two kinds, chosen so that a joint between two blocks carries exactly two
// contacts, one at each end of the shared length (so the joint's normal
// stiffness is k_n = 2·g0/l, the paper's Eq. 4):
//  1. Facing edges: two edges that are anti-parallel (within ~1°), close, and
//     overlap along their length give one contact at each end of the overlap.
//     The contact's vertex is the block vertex that bounds the overlap there;
//     where the two blocks' vertices coincide (within 5 % of the shorter
//     edge, so the choice does not flicker as blocks move) the vertex of the
//     block with the lower id is used. When the overlap is shorter than that
//     5 % band, the two springs are scaled by overlap / band: diagonal
//     neighbours at a four-block junction touch over the tiny length that
//     their neighbours' shear offsets open, and must not stiffen the joints
//     there (with full springs the rock bar's wave speed at g0 = E rises from
//     the paper's 4082 m/s to ~4260 m/s), while a block resting on a corner
//     still gets a growing resistance, without a jump.
//  2. Corners: a convex vertex near the interior of a non-parallel edge whose
//     outside it approaches (its wedge "enters" the edge), and vertex-vertex
//     approaches resolved by Shi's entrance rule: of the four edges meeting at
//     the two vertices, the one whose outside holds the other vertex's wedge
//     most clearly. Corners of aligned blocks that merely touch (the diagonal
//     neighbours at a four-block junction of a regular joint grid) make no
//     contact: the facing edges of the side neighbours carry that junction.
//     Their facing edges are watched instead (AlignedEdges): when one block
//     slides along the joint past the other's corner, the list is searched
//     again, and the facing edges then overlap and make their contacts.
// Neither kind pairs a vertex with an edge it has gone round the corner of
// (passed_corner): such a vertex belongs to the next edge at that corner
// (docs/contact_transfer.md).
#include <span>
#include <utility>
#include <vector>

#include "contact/contact.hpp"
#include "geometry/block_polygons.hpp"

namespace dda {

struct NarrowPhaseSettings {
  double range = 0;            // search distance (m)
  double parallel_sin = 0.02;  // edges within asin(0.02) ≈ 1.1° of anti-parallel face each other
};

// Contacts of the pair (a, b), a < b, appended to `out` (identity, joint from
// `edge_joint` indexed like blocks.vertices, and length; state left Open).
void detect_pair_contacts(const BlockPolygons& blocks, std::span<const int> edge_joint, int a, int b,
                          const NarrowPhaseSettings& settings, std::vector<Contact>& out);

// Whether contact c's vertex has gone round the corner at the nearer end of
// its edge: it lies behind the edge's line by more than its depth behind the
// line of the edge's neighbour at that (convex) corner, plus a margin of
// kCornerMargin of the edge's length. Its "penetration" is then no overlap of
// the blocks (the vertex is outside the edge's block, or nearer the other
// edge) and would push it along the wrong normal: the vertex belongs to the
// next edge at that corner, or to a vertex-vertex contact there.
bool passed_corner(const BlockPolygons& blocks, const Contact& c);
inline constexpr double kCornerMargin = 1e-3;
inline constexpr double kCornerRatio = 10;

// Whether contact c's vertex has slid past an end of its edge, along the
// edge, by more than kEndTie of the shorter of the edge and the longer edge
// at the vertex (where the edge's block turns outwards there, a convex
// corner), or by more than kCornerMargin of the edge (a reflex corner, where
// the vertex runs into the block's next edge at once). No search makes such
// a contact at a convex corner (facing edges place a contact's vertex at
// most their tie, 5 % of the shorter edge, past the end; vertex-edge
// contacts lie inside the edge): the vertex, carried on the edge's line
// beyond its end, would ride on an edge that is not there, or pass through
// the next one into the block.
bool slid_past_end(const BlockPolygons& blocks, const Contact& c);
inline constexpr double kEndTie = 0.05;

// How far every vertex of contact c's two blocks may move (m, each by at
// most this much, by any motion: translation, rotation, strain) with neither
// passed_corner nor slid_past_end able to turn true: a Lipschitz bound of
// the two tests' distances to their thresholds, halved for rounding. 0 where
// a test is true, or its answer does not rest on a distance to spare (a
// vertex deeper than the corner margin). The transfer watch
// (contact/transfer_watch.hpp) runs the exact tests only once the blocks may
// have moved this far.
double transfer_slack(const BlockPolygons& blocks, const Contact& c);

// Two facing edges that touch (normal gap within kCornerMargin of the
// shorter edge) with their ends within the facing edges' tie (kEndTie of the
// shorter edge) of each other along the line: aligned corners, as at a joint
// junction. They have no facing-edge contacts, or contacts scaled down by
// their short overlap; both are right only as long as the blocks do not
// slide along the line. `overlap` is their shared length at the search
// (negative: the gap between their ends).
struct AlignedEdges {
  int a = 0, edge_a = 0, b = 0, edge_b = 0;
  double overlap = 0;
  template <class Archive>
  void fields(Archive& ar) {
    ar(a, edge_a, b, edge_b, overlap);
  }
};

// Whether aligned edges have slid along their line since the search so that
// their overlap grew by more than kAlignedSlide of their tie: the contacts
// between them (none, or scaled by the overlap) are then missing or too
// weak, and the list must be searched again. Also true when the edges no
// longer exist (the blocks changed).
bool aligned_edges_slid(const BlockPolygons& blocks, const AlignedEdges& e);
inline constexpr double kAlignedSlide = 0.1;

// How far every vertex of the two blocks may move with aligned_edges_slid
// staying false (as transfer_slack; 0 where it is true).
double aligned_slack(const BlockPolygons& blocks, const AlignedEdges& e);

// Every pair in parallel; the result is ordered by pair, then identity,
// whatever the thread count. `aligned`, when given, receives the pairs'
// aligned edges, in the same order.
std::vector<Contact> detect_contacts(const BlockPolygons& blocks, std::span<const int> edge_joint,
                                     std::span<const std::pair<int, int>> pairs, const NarrowPhaseSettings& settings,
                                     std::vector<AlignedEdges>* aligned = nullptr);

}  // namespace dda
