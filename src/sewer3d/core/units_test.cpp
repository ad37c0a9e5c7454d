#include "sewer3d/core/units.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sewer3d {
namespace {

TEST(Units, DegreesAndRadians) {
  EXPECT_DOUBLE_EQ(DegToRad(180.0), std::numbers::pi);
  EXPECT_DOUBLE_EQ(RadToDeg(std::numbers::pi / 2.0), 90.0);
  EXPECT_DOUBLE_EQ(DegToRad(360.0), kTwoPi);
  // Round trips within one rounding step over a wide range of angles.
  for (double deg = -720.0; deg <= 720.0; deg += 0.7) {
    EXPECT_NEAR(RadToDeg(DegToRad(deg)), deg, 1e-12 * std::max(1.0, std::abs(deg)));
  }
}

TEST(Units, ClockHours) {
  EXPECT_DOUBLE_EQ(ClockHoursToRad(3.0), std::numbers::pi / 2.0);  // 3 o'clock: a quarter turn
  EXPECT_DOUBLE_EQ(ClockHoursToRad(12.0), kTwoPi);                 // 12 o'clock: a full turn
  EXPECT_NEAR(ClockHoursToRad(1.0), DegToRad(30.0), 1e-15);        // one hour = 30°
}

}  // namespace
}  // namespace sewer3d
