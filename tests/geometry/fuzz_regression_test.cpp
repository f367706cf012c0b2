// Inputs the fuzz targets (fuzz/, docs/fuzzing.md) found crashing or
// tripping a sanitizer, kept as plain tests: each must now be cut, or
// refused with a dda::Error naming the item.
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "cutting_support.hpp"

using namespace dda;
using namespace dda::geometry;

namespace {

std::string error_of(const CutInput& in) {
  try {
    cut_blocks(in);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

CutInput unit_square() {
  CutInput in;
  in.domain = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  return in;
}

// dda_fuzz_geometry: a joint set whose origin lies at 1.2e308 overflowed the
// line numbers (double → long long, UBSan: outside the range of long long).
TEST(FuzzRegression, JointSetOriginFarFromTheDomainIsRefused) {
  for (double x : {1.2e308, 1e20, -1e17}) {
    CutInput in = unit_square();
    in.sets.push_back(geometry::test::persistent_set(0, 0.25, Vec2(0, x)));
    EXPECT_NE(error_of(in).find("joint set 1: its origin lies about"), std::string::npos) << x << ": " << error_of(in);
  }
  CutInput near = unit_square();
  near.sets.push_back(geometry::test::persistent_set(0, 0.25, Vec2(0, 1e6)));  // far, but the line numbers are exact
  EXPECT_EQ(cut_blocks(near).blocks.size(), 4u);
}

}  // namespace
