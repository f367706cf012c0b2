// Contact detection: a joint between two blocks carries exactly two contacts
// (k_n = 2·g0/l, the paper's Eq. 4); touching corners of aligned blocks none.
#include <gtest/gtest.h>

#include <map>

#include "contact/broad_phase.hpp"
#include "contact/narrow_phase.hpp"
#include "scenes.hpp"

using namespace dda;

namespace {

struct Polys {
  std::vector<int> start{0};
  std::vector<Vec2> vertices;
  std::vector<int> joints;
  void add(const std::vector<Vec2>& p) {
    vertices.insert(vertices.end(), p.begin(), p.end());
    joints.insert(joints.end(), p.size(), 0);
    start.push_back(static_cast<int>(vertices.size()));
  }
  BlockPolygons view() const { return {start, vertices}; }
};

std::map<std::pair<int, int>, int> contacts_per_pair(const Polys& p, double range) {
  const auto pairs = find_candidate_pairs(p.view(), range);
  NarrowPhaseSettings s;
  s.range = range;
  std::map<std::pair<int, int>, int> count;
  for (const Contact& c : detect_contacts(p.view(), p.joints, pairs, s))
    ++count[{std::min(c.vblock, c.eblock), std::max(c.vblock, c.eblock)}];
  return count;
}

}  // namespace

TEST(Contacts, RegularGridHasTwoContactsPerJointAndNoneAcrossCorners) {
  Polys p;
  const int n = 4;
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) p.add(test::rectangle(c * 0.2, r * 0.2, 0.2, 0.2));
  const auto count = contacts_per_pair(p, 0.006);
  // 2·n·(n-1) joints, each with two contacts; no diagonal pairs.
  EXPECT_EQ(count.size(), static_cast<std::size_t>(2 * n * (n - 1)));
  for (const auto& [pair, k] : count) {
    const int a = pair.first, b = pair.second;
    const bool side = (b - a == 1 && a / n == b / n) || b - a == n;
    EXPECT_TRUE(side) << "contact across a corner between " << a << " and " << b;
    EXPECT_EQ(k, 2) << "pair " << a << "," << b;
  }
}

TEST(Contacts, RotatedGridBehavesTheSame) {
  Polys p;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) p.add(test::rotated(test::rectangle(c * 2.0, r * 2.0, 2, 2), deg_to_rad(45)));
  const auto count = contacts_per_pair(p, 0.6);  // a wide range, as in the blasting model
  EXPECT_EQ(count.size(), 12u);
  for (const auto& [pair, k] : count) EXPECT_EQ(k, 2);
}

TEST(Contacts, RunningBondGivesContactsAtOverlapEnds) {
  // Upper brick spans x ∈ [0.5, 1.5] over two lower bricks: two joints of
  // length 0.5, each with two contacts, plus the lower bricks' shared joint.
  Polys p;
  p.add(test::rectangle(0, 0, 1, 0.5));
  p.add(test::rectangle(1, 0, 1, 0.5));
  p.add(test::rectangle(0.5, 0.5, 1, 0.5));
  const auto count = contacts_per_pair(p, 0.005);
  EXPECT_EQ(count.at({0, 1}), 2);
  EXPECT_EQ(count.at({0, 2}), 2);
  EXPECT_EQ(count.at({1, 2}), 2);
}

TEST(Contacts, CornerPokingIntoAnEdgeMakesOneContact) {
  Polys p;
  p.add(test::rectangle(0, 0, 2, 1));                                                     // floor block
  p.add({{1.0, 1.001}, {1.5, 1.5}, {1.0, 2.0}, {0.5, 1.5}});                              // a diamond above it
  const auto pairs = find_candidate_pairs(p.view(), 0.01);
  NarrowPhaseSettings s;
  s.range = 0.01;
  const auto contacts = detect_contacts(p.view(), p.joints, pairs, s);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_EQ(contacts[0].vblock, 1);
  EXPECT_EQ(contacts[0].vertex, 0);
  EXPECT_EQ(contacts[0].eblock, 0);
  EXPECT_EQ(contacts[0].edge, 2);  // the floor's top edge (2,1)→(0,1)
}

TEST(Contacts, FarApartBlocksHaveNoCandidatePairs) {
  Polys p;
  p.add(test::rectangle(0, 0, 1, 1));
  p.add(test::rectangle(1.1, 0, 1, 1));
  EXPECT_TRUE(find_candidate_pairs(p.view(), 0.05).empty());
  EXPECT_EQ(find_candidate_pairs(p.view(), 0.2).size(), 1u);
}
