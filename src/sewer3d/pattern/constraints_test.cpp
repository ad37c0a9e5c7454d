#include "sewer3d/pattern/constraints.hpp"

#include <gtest/gtest.h>

#include "sewer3d/pattern/default_pattern.hpp"

namespace sewer3d {
namespace {

TEST(VerifyPattern, DefaultArrayHoldsEveryConstraint) {
  const BinaryArray array = DefaultPatternArray();
  const PatternReport report = VerifyPattern(array, PatternConstraints{});
  EXPECT_TRUE(report.valid) << Describe(report);
  EXPECT_EQ(report.windows, 6 * 200);
  EXPECT_GE(report.min_hamming_found, 3);
  EXPECT_GE(report.min_weight_found, 4);
  EXPECT_EQ(report.adjacent_spot_pairs, 0);
}

TEST(VerifyPattern, DetectsEachKindOfViolation) {
  const PatternConstraints constraints;
  const BinaryArray good = DefaultPatternArray();

  // Two 8-adjacent spots (diagonal, across the wrap-around seam of the torus).
  BinaryArray adjacent = good;
  for (int r = 0; r < 6; ++r) adjacent.set(r, 0, 0), adjacent.set(r, 199, 0), adjacent.set(r, 1, 0);
  adjacent.set(0, 0, 1);
  adjacent.set(5, 199, 1);
  EXPECT_GE(VerifyPattern(adjacent, constraints).adjacent_spot_pairs, 1);
  EXPECT_FALSE(VerifyPattern(adjacent, constraints).valid);

  // An empty array: every window has weight 0 and all windows are identical.
  const BinaryArray empty(6, 20);
  const PatternReport empty_report = VerifyPattern(empty, constraints);
  EXPECT_EQ(empty_report.min_weight_found, 0);
  EXPECT_EQ(empty_report.min_hamming_found, 0);
  EXPECT_GT(empty_report.duplicate_pairs, 0);
  EXPECT_FALSE(empty_report.valid);

  // A period-10 array repeats its windows.
  BinaryArray periodic(6, 20);
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 20; ++c) periodic.set(r, c, good.at(r, c % 10));
  }
  EXPECT_GT(VerifyPattern(periodic, constraints).duplicate_pairs, 0);
}

TEST(VerifyPattern, TorusAndPlainWindowCounts) {
  PatternConstraints plain;
  plain.torus = false;
  EXPECT_EQ(WindowCount(8, 100, plain), 3 * 95);
  EXPECT_EQ(WindowCount(8, 100, PatternConstraints{}), 800);
}

TEST(InferConstraints, TorusForTheShippedArrayPlainOtherwise) {
  const PatternConstraints shipped = InferConstraints(DefaultPatternArray());
  EXPECT_TRUE(shipped.torus);
  EXPECT_EQ(shipped.min_hamming, 3);
  EXPECT_GE(shipped.min_weight, 4);
  EXPECT_TRUE(shipped.isolated);
  // Cut to 6 x 120 the array's wrap-around windows change, but its inner windows stay unique.
  BinaryArray cut(6, 120);
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 120; ++c) cut.set(r, c, DefaultPatternArray().at(r, c));
  }
  const PatternConstraints inferred = InferConstraints(cut);
  EXPECT_EQ(VerifyPattern(cut, inferred).valid, true);
  EXPECT_THROW(InferConstraints(BinaryArray(6, 20)), std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
