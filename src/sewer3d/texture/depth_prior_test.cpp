// The pipe prior and the filling of the decoder's holes from it.

#include "sewer3d/texture/depth_prior.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <opencv2/core.hpp>

#include "sewer3d/testing/pinhole.hpp"

namespace sewer3d {
namespace {

CameraModel Pinhole(int width, int height) { return testing::PinholeCamera(width, height, 500.0); }

// A camera 40 mm above the carrier axis looking up (12 o'clock), y along the axis: a DN300
// wall is 110 mm away on the optical axis, and every prior point lies on the circle.
TEST(PipePrior, DepthLiesOnTheNominalPipe) {
  const CameraModel camera = Pinhole(80, 60);
  Eigen::Matrix3d carrier_from_camera_rotation;
  carrier_from_camera_rotation.col(0) = Eigen::Vector3d::UnitX();
  carrier_from_camera_rotation.col(1) = Eigen::Vector3d::UnitZ();
  carrier_from_camera_rotation.col(2) = -Eigen::Vector3d::UnitY();
  const Rigid3d carrier_from_camera(carrier_from_camera_rotation, Eigen::Vector3d(0, -40, 5));
  const cv::Mat1f prior = PipePriorDepth(camera, carrier_from_camera, 300.0);
  EXPECT_NEAR(prior(30, 40) + prior(29, 39), 2 * 110.0, 0.5);
  for (int v = 0; v < prior.rows; ++v) {
    for (int u = 0; u < prior.cols; ++u) {
      ASSERT_TRUE(std::isfinite(prior(v, u)));
      const auto xy = camera.Unproject({double(u), double(v)});
      const Eigen::Vector3d p =
          carrier_from_camera * (Eigen::Vector3d(xy->x(), xy->y(), 1.0) * double(prior(v, u)));
      EXPECT_NEAR(std::hypot(p.x(), p.y()), 150.0, 1e-3);
    }
  }
  // Nothing measured: the prior as it is.
  const cv::Mat1f none(prior.size(), std::numeric_limits<float>::quiet_NaN());
  const cv::Mat1f as_prior = FillDepthFromPrior(none, prior);
  EXPECT_EQ(cv::norm(as_prior, prior, cv::NORM_INF), 0.0);
  // A camera outside the pipe sees no prior.
  const Rigid3d outside(carrier_from_camera_rotation, Eigen::Vector3d(0, -200, 0));
  EXPECT_EQ(cv::countNonZero(PipePriorDepth(camera, outside, 300.0) > 0), 0);
}

// A measured patch 2 % farther than the prior (the carrier off the pipe's axis): the holes take
// the prior scaled to meet it, so the filled map has no step at the patch's border (a step
// would turn into false normals and a bright seam in the shading correction). The largest
// difference between neighbouring pixels anywhere stays at the prior's own slope.
TEST(PipePrior, FilledDepthMeetsTheMeasuredDepthWithoutAStep) {
  cv::Mat1f prior(60, 80);
  for (int v = 0; v < prior.rows; ++v) {
    for (int u = 0; u < prior.cols; ++u) prior(v, u) = 110.0F + 0.05F * float(u);
  }
  cv::Mat1f depth(prior.size(), std::numeric_limits<float>::quiet_NaN());
  for (int v = 20; v < 40; ++v) {
    for (int u = 25; u < 55; ++u) depth(v, u) = 1.02F * prior(v, u);
  }
  const cv::Mat1f filled = FillDepthFromPrior(depth, prior);
  EXPECT_EQ(filled(30, 40), depth(30, 40));             // measured pixels unchanged
  EXPECT_NEAR(filled(5, 5), 1.02 * prior(5, 5), 0.01);  // far away: the same ratio
  double worst_step = 0.0;
  for (int v = 0; v < filled.rows; ++v) {
    for (int u = 1; u < filled.cols; ++u)
      worst_step = std::max(worst_step, double(std::abs(filled(v, u) - filled(v, u - 1))));
  }
  EXPECT_LT(worst_step, 0.06);  // 1.02 x the prior's 0.05 mm per pixel, no step of 2.2 mm
}

}  // namespace
}  // namespace sewer3d
