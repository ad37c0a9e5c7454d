#include "sewer3d/simeval/residual_image.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace sewer3d {
namespace {

TEST(ResidualImage, RangeIsARoundThreeRms) {
  EXPECT_DOUBLE_EQ(ResidualRange({0.06, -0.06}), 0.2);  // 3 RMS = 0.18
  EXPECT_DOUBLE_EQ(ResidualRange({0.02, -0.02, NAN}), 0.1);
  EXPECT_DOUBLE_EQ(ResidualRange({0.4, -0.4}), 2.0);
  EXPECT_DOUBLE_EQ(ResidualRange({}), 0.05);
}

TEST(ResidualImage, RayResidualsAreSignedAlongTheRay) {
  Scene plane;
  plane.type = Scene::Type::kPlane;
  plane.distance_mm = 100.0;
  const Eigen::Vector3d on(10.0, -5.0, 100.0);
  const std::vector<double> r =
      RayResiduals(plane, {on * 1.002, on * 0.999, Eigen::Vector3d(0.0, 0.0, -50.0)});
  ASSERT_EQ(r.size(), 3u);
  EXPECT_NEAR(r[0], 0.002 * on.norm(), 1e-9);   // beyond the surface: positive
  EXPECT_NEAR(r[1], -0.001 * on.norm(), 1e-9);  // in front of it: negative
  EXPECT_TRUE(std::isnan(r[2]));                // behind the camera: the ray misses
}

// A bowl: a plane at 100 mm whose points sink toward the camera at the centre (−) and rise at
// the corners (+). The picture shows the centre blue, the corners red, the view's aspect that
// of the cloud.
TEST(ResidualImage, ABowlIsBlueInTheMiddleAndRedAtTheCorners) {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> residuals;
  for (int v = -30; v <= 30; ++v) {
    for (int u = -40; u <= 40; ++u) {
      points.emplace_back(u, v, 100.0);
      residuals.push_back(0.1 * ((u * u + v * v) / 1250.0 - 1.0));
    }
  }
  ResidualImageOptions options;
  options.width_px = 400;
  options.range_mm = 0.1;
  const cv::Mat3b image = ResidualImage(points, residuals, options);
  const int left = 20, top = 40, width = 400, height = 300;  // the view's place and size
  EXPECT_EQ(image.rows, top + height + 20);
  EXPECT_EQ(image.cols, left + width + 130);
  const cv::Vec3b centre = image(top + height / 2, left + width / 2);
  const cv::Vec3b corner = image(top + 2, left + width - 3);
  EXPECT_GT(centre[0], centre[2] + 100);  // BGR: blue
  EXPECT_GT(corner[2], corner[0] + 100);  // red
  EXPECT_THROW(ResidualImage(points, {0.1}, options), std::invalid_argument);
}

// Two pictures from the fit, two more with the truth; points on the true plane are white there.
TEST(ResidualImage, PicturesOfAFitAndOfTheTruth) {
  Scene plane;
  plane.type = Scene::Type::kPlane;
  plane.distance_mm = 100.0;
  std::vector<Eigen::Vector3d> points;
  for (int v = -30; v <= 30; v += 2)
    for (int u = -40; u <= 40; u += 2) points.emplace_back(u, v, 100.0);
  const std::vector<double> fitted(points.size(), 0.01);
  EXPECT_EQ(ResidualPictures(points, fitted, "fit", nullptr).size(), 2u);
  const std::vector<NamedPicture> all = ResidualPictures(points, fitted, "fit", &plane);
  ASSERT_EQ(all.size(), 4u);
  EXPECT_EQ(all[0].file, "residuals.png");
  EXPECT_EQ(all[3].file, "truth_residuals_smoothed.png");
  const cv::Vec3b centre = all[2].image(40 + 150, 20 + 400);  // the view's middle
  EXPECT_GT(std::min({centre[0], centre[1], centre[2]}), 240);
}

}  // namespace
}  // namespace sewer3d
