#include "sewer3d/camera/camera_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <random>

#include "sewer3d/core/units.hpp"

namespace sewer3d {
namespace {

// A 2592 x 1944 camera whose distorted field spans 76° horizontally.
CameraIntrinsics WideCamera(std::array<double, 3> k) {
  CameraIntrinsics c;
  c.width = 2592;
  c.height = 1944;
  const double x_edge = std::tan(DegToRad(38.0));
  const double r2 = x_edge * x_edge;
  const double xd_edge = x_edge * (1 + r2 * (k[0] + r2 * (k[1] + r2 * k[2])));
  c.fx = c.fy = 1296.0 / xd_edge;
  c.cx = 1295.5;
  c.cy = 971.5;
  c.k = k;
  return c;
}

std::vector<Eigen::Vector2d> ImageGrid(const CameraIntrinsics& c, int step) {
  std::vector<Eigen::Vector2d> pixels;
  for (int v = 0; v <= c.height; v += step) {
    for (int u = 0; u <= c.width; u += step) {
      pixels.emplace_back(std::min(u - 0.5, c.width - 0.5), std::min(v - 0.5, c.height - 0.5));
    }
  }
  return pixels;
}

cv::Mat CameraMatrix(const CameraIntrinsics& c) {
  return (cv::Mat_<double>(3, 3) << c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
}
cv::Mat DistCoeffs(const CameraIntrinsics& c) {
  return (cv::Mat_<double>(1, 5) << c.k[0], c.k[1], 0.0, 0.0, c.k[2]);
}

TEST(CameraModel, ProjectAgreesWithOpenCV) {
  for (const auto& k :
       {std::array<double, 3>{-0.3, 0.1, -0.01}, std::array<double, 3>{0.05, -0.02, 0.004}}) {
    const CameraModel camera(WideCamera(k));
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> xy(-0.8, 0.8), z(50.0, 300.0);
    std::vector<cv::Point3d> points;
    for (int i = 0; i < 2000; ++i) {
      const double depth = z(rng);
      points.emplace_back(xy(rng) * depth, xy(rng) * depth * 0.8, depth);
    }
    std::vector<cv::Point2d> reference;
    cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0),
                      CameraMatrix(camera.intrinsics()), DistCoeffs(camera.intrinsics()),
                      reference);
    for (size_t i = 0; i < points.size(); ++i) {
      const auto pixel = camera.Project({points[i].x, points[i].y, points[i].z});
      ASSERT_TRUE(pixel.has_value());
      EXPECT_NEAR(pixel->x(), reference[i].x, 1e-6);
      EXPECT_NEAR(pixel->y(), reference[i].y, 1e-6);
    }
  }
}

TEST(CameraModel, UnprojectInvertsProjectOverWholeImageWithStrongBarrel) {
  const CameraModel camera(WideCamera({-0.3, 0.1, 0.0}));
  ASSERT_TRUE(camera.WholeImageInvertible());
  double worst_px = 0.0;
  for (const auto& pixel : ImageGrid(camera.intrinsics(), 16)) {
    const auto ray = camera.Ray(pixel);
    ASSERT_TRUE(ray.has_value()) << pixel.transpose();
    const auto back = camera.Project(*ray * 123.0);
    ASSERT_TRUE(back.has_value());
    worst_px = std::max(worst_px, (*back - pixel).norm());
  }
  EXPECT_LT(worst_px, 1e-6);
}

TEST(CameraModel, UnprojectAgreesWithOpenCVWhereItConverges) {
  const CameraModel camera(WideCamera({-0.3, 0.1, 0.0}));
  const auto grid = ImageGrid(camera.intrinsics(), 64);
  std::vector<cv::Point2d> pixels;
  for (const auto& p : grid) pixels.emplace_back(p.x(), p.y());
  std::vector<cv::Point2d> reference;
  cv::undistortPoints(
      pixels, reference, CameraMatrix(camera.intrinsics()), DistCoeffs(camera.intrinsics()),
      cv::noArray(), cv::noArray(),
      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 500, 1e-15));
  int compared = 0;
  for (size_t i = 0; i < grid.size(); ++i) {
    // OpenCV's fixed-point iteration does not always converge near the corners; compare only
    // where its own answer re-projects onto the pixel.
    const auto reprojected = camera.Project({reference[i].x, reference[i].y, 1.0});
    if (!reprojected || (*reprojected - grid[i]).norm() > 1e-9) continue;
    const auto ours = camera.Unproject(grid[i]);
    ASSERT_TRUE(ours.has_value());
    EXPECT_NEAR(ours->x() * camera.intrinsics().fx, reference[i].x * camera.intrinsics().fx, 1e-6);
    EXPECT_NEAR(ours->y() * camera.intrinsics().fy, reference[i].y * camera.intrinsics().fy, 1e-6);
    ++compared;
  }
  EXPECT_GT(compared, static_cast<int>(grid.size() * 3 / 4));
}

TEST(CameraModel, ReportsPixelsBeyondTheFold) {
  // k1 = -0.3 alone: r_d = r (1 - 0.3 r²) peaks at r = 1/sqrt(0.9), r_d = 0.703. The corners of
  // a 76° x 61° image (distorted radius ~0.80) cannot be unprojected and must say so.
  const CameraModel camera(WideCamera({-0.3, 0.0, 0.0}));
  EXPECT_NEAR(camera.fold_radius(), 1.0 / std::sqrt(0.9), 1e-9);
  EXPECT_NEAR(camera.fold_radius_distorted(), (1.0 / std::sqrt(0.9)) * (1.0 - 0.3 / 0.9), 1e-9);
  EXPECT_FALSE(camera.WholeImageInvertible());
  EXPECT_FALSE(camera.Unproject({-0.5, -0.5}).has_value());
  EXPECT_FALSE(camera.Ray({2591.5, 1943.5}).has_value());
  // A ray beyond the fold is not projected either (its pixel would be ambiguous).
  EXPECT_FALSE(camera.Project({1.2, 0.0, 1.0}).has_value());
  // Everything inside the fold still round-trips.
  int valid = 0;
  for (const auto& pixel : ImageGrid(camera.intrinsics(), 32)) {
    const auto ray = camera.Ray(pixel);
    if (!ray) {
      EXPECT_GE(camera.PixelToDistorted(pixel).norm(), camera.fold_radius_distorted() - 1e-12);
      continue;
    }
    ++valid;
    EXPECT_LT((*camera.Project(*ray) - pixel).norm(), 1e-6);
  }
  EXPECT_GT(valid, 0);
}

TEST(CameraModel, RayIsUnitAndBehindCameraIsRejected) {
  const CameraModel camera(WideCamera({-0.1, 0.0, 0.0}));
  const auto ray = camera.Ray({100.0, 1800.0});
  ASSERT_TRUE(ray.has_value());
  EXPECT_NEAR(ray->norm(), 1.0, 1e-12);
  EXPECT_GT(ray->z(), 0.0);
  EXPECT_FALSE(camera.Project({0.0, 0.0, -5.0}).has_value());
  EXPECT_FALSE(camera.Project({0.0, 0.0, 0.0}).has_value());
}

TEST(CameraModel, RejectsBadIntrinsics) {
  CameraIntrinsics c = WideCamera({0, 0, 0});
  c.fx = 0.0;
  EXPECT_THROW(CameraModel{c}, std::invalid_argument);
  c = WideCamera({0, 0, 0});
  c.width = -3;
  EXPECT_THROW(CameraModel{c}, std::invalid_argument);
  c = WideCamera({0, 0, 0});
  c.k[1] = std::nan("");
  EXPECT_THROW(CameraModel{c}, std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
