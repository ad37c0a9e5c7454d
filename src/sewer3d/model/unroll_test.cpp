#include "sewer3d/model/unroll.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "sewer3d/model/axis_curve.hpp"

namespace sewer3d {
namespace {

constexpr double kPi = std::numbers::pi;

// A 2 m arc of 3 m bend radius (tighter than any sewer bend) through (5, −3, 0), tilted.
Centreline BentCentreline() {
  const Eigen::Vector3d t0 = Eigen::Vector3d(0.02, 0.03, 1.0).normalized();
  const Eigen::Vector3d n0 = (Eigen::Vector3d::UnitX() - t0.x() * t0).normalized();
  std::vector<Eigen::Vector3d> curve;
  for (double s = -500.0; s <= 1500.0; s += 1.0) {
    curve.push_back(Eigen::Vector3d(5, -3, 0) + 3000.0 * std::sin(s / 3000.0) * t0 +
                    3000.0 * (1.0 - std::cos(s / 3000.0)) * n0);
  }
  auto line = ResampleAxis(curve, 10.0);
  EXPECT_TRUE(line.has_value());
  return *line;
}

TEST(Unroll, ClockConventionOnAStraightAxis) {
  const auto line = ResampleAxis({{0, 0, -100}, {0, 0, 100}}, 10.0);
  ASSERT_TRUE(line.has_value());
  EXPECT_NEAR(line->station0_mm, -100.0, 1e-9);
  const CylPoint crown = Unroll(*line, {0, -150, 20});  // y is down: −y is the crown
  EXPECT_NEAR(crown.clock_rad, 0.0, 1e-12);
  EXPECT_NEAR(crown.station_mm, 20.0, 1e-9);
  EXPECT_NEAR(crown.radius_mm, 150.0, 1e-9);
  EXPECT_NEAR(Unroll(*line, {150, 0, 0}).clock_rad, kPi / 2, 1e-12);  // 3 o'clock = +x
  EXPECT_NEAR(Unroll(*line, {0, 150, 0}).clock_rad, kPi, 1e-12);      // invert
  EXPECT_NEAR(Unroll(*line, {-150, 0, 0}).clock_rad, 1.5 * kPi, 1e-12);
}

TEST(Unroll, RoundTripOnABentTiltedAxis) {
  const Centreline line = BentCentreline();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> station(-600.0, 1600.0), clock(0.0, 2 * kPi),
      radius(100.0, 200.0);
  double worst_station = 0, worst_clock = 0, worst_radius = 0;
  for (int i = 0; i < 20000; ++i) {
    const CylPoint truth{station(rng), clock(rng), radius(rng)};
    const Eigen::Vector3d p =
        line.FrameAt(truth.station_mm).origin +
        truth.radius_mm * line.FrameAt(truth.station_mm).Direction(truth.clock_rad);
    EXPECT_LT((PointAt(line, truth) - p).norm(), 1e-12);
    const CylPoint back = Unroll(line, p, i % 2 == 0 ? 0.0 : truth.station_mm + 30.0);
    worst_station = std::max(worst_station, std::abs(back.station_mm - truth.station_mm));
    const double dc = std::remainder(back.clock_rad - truth.clock_rad, 2 * kPi);
    worst_clock = std::max(worst_clock, std::abs(dc) * truth.radius_mm);
    worst_radius = std::max(worst_radius, std::abs(back.radius_mm - truth.radius_mm));
  }
  EXPECT_LT(worst_station, 1e-6);
  EXPECT_LT(worst_clock, 1e-6);  // mm along the wall
  EXPECT_LT(worst_radius, 1e-6);
}

TEST(Unroll, FrameIsContinuousAndOrthonormal) {
  const Centreline line = BentCentreline();
  for (double s = -600.0; s < 1600.0; s += 0.7) {
    const AxisFrame a = line.FrameAt(s), b = line.FrameAt(s + 1e-6);
    EXPECT_NEAR(a.tangent.norm(), 1.0, 1e-12);
    EXPECT_NEAR(a.crown.dot(a.tangent), 0.0, 1e-12);
    EXPECT_NEAR(a.right.dot(a.crown), 0.0, 1e-12);
    EXPECT_LT((a.tangent - b.tangent).norm(), 1e-8);
    EXPECT_LT((a.origin - b.origin).norm(), 2e-6);
  }
}

TEST(WrapClock, IntoOneTurn) {
  EXPECT_NEAR(WrapClock(-0.5), 2 * kPi - 0.5, 1e-12);
  EXPECT_NEAR(WrapClock(2 * kPi + 0.25), 0.25, 1e-12);
  EXPECT_EQ(WrapClock(0.0), 0.0);
}

}  // namespace
}  // namespace sewer3d
