#include "sewer3d/core/circle_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace sewer3d {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(FitCircleRobust, IgnoresFortyPercentOfPointsOffTheWall) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> angle(0.0, 2 * kPi), inward(3.0, 40.0);
  const Eigen::Vector2d centre(7.0, -4.0);
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 500; ++i) {
    const double t = angle(rng);
    // 40 % of the points (deposits, intrusions) lie 3–40 mm inside the wall.
    const bool outlier = i % 5 < 2;
    const double r = 150.0 - (outlier ? inward(rng) : 0.0);
    points.push_back(centre + r * Eigen::Vector2d(std::cos(t), std::sin(t)));
  }
  const CircleFit fit = FitCircleRobust(points, CircleFitOptions{});
  ASSERT_TRUE(fit.converged);
  EXPECT_LT((fit.centre - centre).norm(), 1e-6);
  EXPECT_NEAR(fit.radius_mm, 150.0, 1e-6);
  EXPECT_NEAR(fit.inlier_fraction, 0.6, 1e-9);
  EXPECT_EQ(fit.coverage_deg, 360.0);
}

TEST(FitCircleRobust, KeepsTheCircleOfAnOvalPipe) {
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 360; ++i) {
    const double t = 2 * kPi * i / 360;
    const double r = 150.0 * (1.0 + 0.03 * std::cos(2 * t + 0.4));  // 6 % ovality
    points.push_back(Eigen::Vector2d(1, 2) + r * Eigen::Vector2d(std::cos(t), std::sin(t)));
  }
  const CircleFit fit = FitCircleRobust(points, CircleFitOptions{});
  ASSERT_TRUE(fit.converged);
  EXPECT_LT((fit.centre - Eigen::Vector2d(1, 2)).norm(), 0.01);
  EXPECT_NEAR(fit.radius_mm, 150.0, 0.01);  // the mean radius, not an axis of the ellipse
  EXPECT_NEAR(fit.ovality_mm, 4.5, 0.02);
  EXPECT_FALSE(FitCircleRobust({points.begin(), points.begin() + 5}, {}).converged);
}

}  // namespace
}  // namespace sewer3d
