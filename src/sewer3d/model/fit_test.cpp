#include "sewer3d/model/fit.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

namespace sewer3d {
namespace {

TEST(FitPlane, RecoversTiltedPlaneAndNoiseLevel) {
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::uniform_real_distribution<double> xy(-60.0, 60.0);
  const Eigen::Vector3d n = Eigen::Vector3d(0.0, 0.2, -1.0).normalized();
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 5000; ++i) {
    const double x = xy(rng), y = xy(rng);
    const double z = 140.0 - (n.x() * x + n.y() * y) / n.z();  // n·(p − (0,0,140)) = 0
    points.push_back(Eigen::Vector3d(x, y, z) + n * noise(rng));
  }
  const auto fit = FitPlane(points);
  ASSERT_TRUE(fit.has_value());
  EXPECT_LT(std::acos(std::min(1.0, fit->normal.dot(n))), 1e-3);
  EXPECT_NEAR(-fit->offset / fit->normal.z(), 140.0, 0.01);  // z at the optical axis
  EXPECT_NEAR(fit->rms_mm, 0.05, 0.003);                     // 5000 samples: ~1 %
}

TEST(FitCylinder, RecoversDecentredTiltedCylinderFromAPatch) {
  std::mt19937 rng(2);
  std::normal_distribution<double> noise(0.0, 0.1);
  std::uniform_real_distribution<double> angle(-0.6, 0.6), along(-60.0, 60.0);
  const Eigen::Vector3d axis = Eigen::Vector3d(0.05, 1.0, 0.02).normalized();
  const Eigen::Vector3d centre(6.0, 0.0, -12.0);
  const Eigen::Vector3d e1 = (Eigen::Vector3d::UnitZ() - axis.z() * axis).normalized(),
                        e2 = axis.cross(e1);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 4000; ++i) {
    const double t = angle(rng);
    const double r = 150.0 + noise(rng);
    points.push_back(centre + axis * along(rng) + r * (std::cos(t) * e1 + std::sin(t) * e2));
  }
  const auto fit = FitCylinder(points, Eigen::Vector3d::UnitY());
  ASSERT_TRUE(fit.has_value());
  EXPECT_TRUE(fit->converged);
  EXPECT_NEAR(fit->radius_mm, 150.0, 0.1);
  EXPECT_LT(std::acos(std::min(1.0, std::abs(fit->axis_direction.dot(axis)))), 2e-3);
  EXPECT_NEAR(fit->rms_mm, 0.1, 0.005);
  EXPECT_FALSE(fit->flat);
  EXPECT_GT(fit->plane_rms_mm, 1.0);  // a 69° arc of r 150 mm is far from flat
}

TEST(FitCylinder, TellsAFlatCloud) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::uniform_real_distribution<double> xy(-60.0, 60.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 3000; ++i) points.emplace_back(xy(rng), xy(rng), 140.0 + noise(rng));
  const auto fit = FitCylinder(points, Eigen::Vector3d::UnitY());
  ASSERT_TRUE(fit.has_value());  // some huge cylinder: only `flat` tells it measures nothing
  EXPECT_TRUE(fit->flat) << "plane RMS " << fit->plane_rms_mm << ", cylinder " << fit->rms_mm;
  EXPECT_NEAR(fit->plane_rms_mm, 0.05, 0.004);
}

TEST(InnerPoints, KeepsTheCentralPartOfTheView) {
  std::vector<Eigen::Vector3d> points;
  for (int i = -10; i <= 10; ++i) {
    for (int j = -10; j <= 10; ++j) points.emplace_back(i * 10.0, j * 10.0, 100.0);
  }
  EXPECT_EQ(InnerPoints(points, 0.5).size(), 11u * 11u);
  EXPECT_EQ(InnerPoints(points, 1.0).size(), points.size());
}

}  // namespace
}  // namespace sewer3d
