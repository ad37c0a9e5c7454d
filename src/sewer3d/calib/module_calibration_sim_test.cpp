// Module calibration on exact synthetic correspondences with pixel noise, and the corner
// transfer by local homographies.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <random>

#include "sewer3d/calib/camera_calibration.hpp"
#include "sewer3d/calib/module_calibration.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/sim/board.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

TEST(ModuleCalibration, RecoversCameraProjectorAndExtrinsics) {
  const ModuleDescription truth = testing::SmallDefaultModule(1296);
  Checkerboard board;
  const auto poses = RandomBoardPoses(truth, board, 20, 5);
  const auto corners = BoardCorners(board.cols, board.rows, board.square_mm);
  const CameraModel camera(truth.camera), projector(truth.projector);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.1);  // px, a good corner detector's
  std::vector<ModuleCalibrationView> views;
  for (const Rigid3d& pose : poses) {
    ModuleCalibrationView v;
    for (const Eigen::Vector3d& x : corners) {
      const Eigen::Vector3d p = pose * x;
      v.camera_corners.push_back(*camera.Project(p) + Eigen::Vector2d(noise(rng), noise(rng)));
      v.projector_corners.push_back(*projector.Project(truth.projector_from_camera * p) +
                                    Eigen::Vector2d(noise(rng), noise(rng)));
    }
    views.push_back(v);
  }
  const ModuleCalibrationResult r =
      CalibrateModule(views, corners, truth.camera.width, truth.camera.height,
                      truth.projector.width, truth.projector.height);
  EXPECT_TRUE(r.converged);
  // RMS of 2-D residuals with σ = 0.1 px per coordinate: 0.1 √2, less the fitted freedom.
  EXPECT_NEAR(r.camera_rms_px, 0.1 * std::sqrt(2.0), 0.01);
  EXPECT_NEAR(r.projector_rms_px, 0.1 * std::sqrt(2.0), 0.01);
  // The bounds: focal lengths 0.1 %, principal points 1 px, baseline 0.1 mm, 0.05°.
  EXPECT_NEAR(r.camera.fx / truth.camera.fx, 1.0, 1e-3);
  EXPECT_NEAR(r.projector.fy / truth.projector.fy, 1.0, 1e-3);
  EXPECT_NEAR(r.camera.cx, truth.camera.cx, 1.0);
  EXPECT_NEAR(r.projector.cy, truth.projector.cy, 1.0);
  const double baseline = r.projector_from_camera.translation.norm();
  EXPECT_NEAR(baseline, truth.projector_from_camera.translation.norm(), 0.1);
  EXPECT_LT(RadToDeg(r.projector_from_camera.rotation.angularDistance(
                truth.projector_from_camera.rotation)),
            0.05);
  EXPECT_GT(r.sigma[8], 0.0);
}

TEST(CornerTransfer, FollowsTheLocalHomography) {
  Eigen::Matrix3d h;
  h << 1.1, 0.05, 30.0, -0.02, 0.95, 12.0, 1e-5, 2e-5, 1.0;
  std::vector<Eigen::Vector2d> camera, projector;
  for (int y = 0; y < 400; y += 8) {
    for (int x = 0; x < 400; x += 8) {
      const Eigen::Vector3d q = h * Eigen::Vector3d(x, y, 1.0);
      camera.emplace_back(x, y);
      projector.push_back(q.head<2>() / q.z());
    }
  }
  projector[1000] += Eigen::Vector2d(40.0, 0.0);  // a wrong decode: RANSAC drops it
  const std::vector<Eigen::Vector2d> corners{{200.5, 199.25}, {1000.0, 1000.0}};
  const auto out = CornersInProjector(corners, camera, projector);
  ASSERT_TRUE(out[0].has_value());
  const Eigen::Vector3d q = h * Eigen::Vector3d(200.5, 199.25, 1.0);
  EXPECT_LT((*out[0] - q.head<2>() / q.z()).norm(), 1e-5);  // findHomography refines to ~1e-6 px
  EXPECT_FALSE(out[1].has_value());                         // no spots near it
}

TEST(CornerTransfer, UndistortedFitIsExactOnALensDistortedPlane) {
  // A plane seen by the default module (k1 = -0.08 on both sides): the camera -> projector map
  // is a homography only between undistorted coordinates.
  const ModuleDescription truth = testing::SmallDefaultModule(1296);
  const CameraModel camera(truth.camera), projector(truth.projector);
  const Eigen::Vector3d normal = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
  const double distance = 120.0;  // mm, plane n.x = d
  std::vector<Eigen::Vector2d> camera_px, projector_px;
  for (int y = 20; y < truth.camera.height - 20; y += 9) {
    for (int x = 20; x < truth.camera.width - 20; x += 9) {
      const auto ray = camera.Ray(Eigen::Vector2d(x, y));
      ASSERT_TRUE(ray.has_value());
      const Eigen::Vector3d p = *ray * (distance / normal.dot(*ray));
      const auto q = projector.Project(truth.projector_from_camera * p);
      if (!q || q->x() < 0 || q->y() < 0 || q->x() > truth.projector.width - 1 ||
          q->y() > truth.projector.height - 1) {
        continue;
      }
      camera_px.emplace_back(x, y);
      projector_px.push_back(*q);
    }
  }
  // Two corners near the image's corners, where distortion bends the pixel map most, one central.
  const std::vector<Eigen::Vector2d> corners{{150.3, 140.7}, {1150.2, 830.9}, {640.0, 480.0}};
  std::vector<Eigen::Vector2d> expected;
  for (const auto& c : corners) {
    const Eigen::Vector3d ray = *camera.Ray(c);
    expected.push_back(
        *projector.Project(truth.projector_from_camera * (ray * (distance / normal.dot(ray)))));
  }
  const auto in_pixels = CornersInProjector(corners, camera_px, projector_px);
  CornerTransferOptions undistorted;
  undistorted.camera = truth.camera;
  undistorted.projector = truth.projector;
  const auto exact = CornersInProjector(corners, camera_px, projector_px, undistorted);
  double worst_pixels = 0.0;
  for (size_t i = 0; i < corners.size(); ++i) {
    ASSERT_TRUE(in_pixels[i].has_value() && exact[i].has_value());
    worst_pixels = std::max(worst_pixels, (*in_pixels[i] - expected[i]).norm());
    EXPECT_LT((*exact[i] - expected[i]).norm(), 1e-4) << "corner " << i;
  }
  // The pixel fit's bending error is what the second pass removes: visible at the edge.
  EXPECT_GT(worst_pixels, 0.05);  // 0.18 px measured
  std::printf("corner transfer, pixel homography: worst error %.4f px\n", worst_pixels);
  // The second pass over a view replaces its pixel-fit corners by the exact ones.
  std::vector<ModuleCalibrationView> views{
      {corners, {*in_pixels[0], *in_pixels[1], *in_pixels[2]}}};
  ASSERT_EQ(RetransferCorners(views, {{camera_px, projector_px}}, truth.camera, truth.projector),
            1);
  for (size_t i = 0; i < corners.size(); ++i) {
    EXPECT_LT((views[0].projector_corners[i] - expected[i]).norm(), 1e-4) << "corner " << i;
  }
}

}  // namespace
}  // namespace sewer3d
