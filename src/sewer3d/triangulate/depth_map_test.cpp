// Depth-map interpolation on a tilted plane seen by a pinhole camera, where inverse depth is
// an affine function of the pixel: the map must be exact to float precision inside triangles,
// empty across long edges, and tight enough to tell 1/z interpolation from linear z.

#include "sewer3d/triangulate/depth_map.hpp"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <random>

namespace sewer3d {
namespace {

// The plane n · X = d (camera frame, mm) through a pinhole camera of focal f px, centre c:
// z = d / (n · ray) from 64 to 182 mm over a 640 x 480 image.
struct TiltedPlane {
  Eigen::Vector3d normal = Eigen::Vector3d(0.6, 0.2, 1.0).normalized();  // 32° from the axis
  double distance_mm = 80.0;
  double focal_px = 500.0;
  Eigen::Vector2d centre_px{320.0, 240.0};

  double Depth(const Eigen::Vector2d& px) const {
    const Eigen::Vector3d ray(((px - centre_px) / focal_px).x(), ((px - centre_px) / focal_px).y(),
                              1.0);
    return distance_mm / normal.dot(ray);
  }
};

// Float precision of a depth: the map stores float, so half an ulp of the rounding plus the
// double arithmetic before it; 2 ulps covers both.
double FloatTolerance(double z_mm) { return 2.0 * FLT_EPSILON * z_mm; }

TEST(DepthMap, TiltedPlaneIsExactToFloatPrecisionInsideTriangles) {
  const TiltedPlane plane;
  const cv::Size size(640, 480);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-2.0, 2.0);
  std::vector<Eigen::Vector2d> pixels;
  std::vector<double> depths;
  for (double v = 20.0; v <= 460.0; v += 8.0) {
    for (double u = 20.0; u <= 620.0; u += 8.0) {
      pixels.emplace_back(u + jitter(rng), v + jitter(rng));
      depths.push_back(plane.Depth(pixels.back()));
    }
  }
  // Jittered 8 px grid: Delaunay edges are at most ~16 px.
  const cv::Mat1f depth = InterpolateDepth(size, pixels, depths, 20.0);
  double worst_ulps = 0.0;
  for (int v = 0; v < size.height; ++v) {
    for (int u = 0; u < size.width; ++u) {
      // Inside the jittered grid (2 px from its outer points' extremes) every pixel has depth.
      if (u >= 24 && u <= 616 && v >= 24 && v <= 456) {
        ASSERT_FALSE(std::isnan(depth(v, u))) << u << ", " << v;
      }
      if (std::isnan(depth(v, u))) continue;
      const double truth = plane.Depth({u, v});
      worst_ulps = std::max(worst_ulps, std::abs(depth(v, u) - truth) / (FLT_EPSILON * truth));
      ASSERT_LE(std::abs(depth(v, u) - truth), FloatTolerance(truth)) << u << ", " << v;
    }
  }
  RecordProperty("worst_error_in_float_epsilons", std::to_string(worst_ulps));
}

TEST(DepthMap, LinearDepthWouldMissTheTolerance) {
  // One triangle of the grid's size on the same plane: z interpolated linearly between its
  // corners departs from the plane by z'' h² / 8 ≈ hundredths of a millimetre, far above float
  // precision, while 1/z interpolation (what InterpolateDepth does) stays exact.
  const TiltedPlane plane;
  const std::vector<Eigen::Vector2d> pixels{{100.0, 100.0}, {116.0, 100.0}, {100.0, 116.0}};
  std::vector<double> depths;
  for (const auto& p : pixels) depths.push_back(plane.Depth(p));
  const cv::Mat1f depth = InterpolateDepth({200, 200}, pixels, depths, 30.0);
  double worst_map = 0.0, worst_linear = 0.0;
  int inside = 0;
  for (int v = 100; v <= 116; ++v) {
    for (int u = 100; u <= 116; ++u) {
      const double wb = (u - 100.0) / 16.0, wc = (v - 100.0) / 16.0, wa = 1.0 - wb - wc;
      if (wa < 0.0) {
        EXPECT_TRUE(std::isnan(depth(v, u))) << u << ", " << v;
        continue;
      }
      ++inside;
      const double truth = plane.Depth({u, v});
      const double linear = wa * depths[0] + wb * depths[1] + wc * depths[2];
      ASSERT_FALSE(std::isnan(depth(v, u))) << u << ", " << v;
      worst_map = std::max(worst_map, std::abs(depth(v, u) - truth) / FloatTolerance(truth));
      worst_linear = std::max(worst_linear, std::abs(linear - truth) / FloatTolerance(truth));
    }
  }
  EXPECT_EQ(inside, 17 * 18 / 2);
  EXPECT_LE(worst_map, 1.0);
  EXPECT_GT(worst_linear, 100.0);
  RecordProperty("linear_z_error_in_tolerances", std::to_string(worst_linear));
}

TEST(DepthMap, TrianglesWithALongEdgeStayEmpty) {
  const TiltedPlane plane;
  // Two patches of an 8 px grid 60 px apart: the triangles bridging the gap have edges of at
  // least 60 px.
  std::vector<Eigen::Vector2d> pixels;
  std::vector<double> depths;
  for (double v = 100.0; v <= 200.0; v += 8.0) {
    for (double u : {100.0, 108.0, 116.0, 124.0, 184.0, 192.0, 200.0, 208.0}) {
      pixels.emplace_back(u, v + 0.25 * u / 8.0);  // sheared: no four points on a circle
      depths.push_back(plane.Depth(pixels.back()));
    }
  }
  const cv::Mat1f depth = InterpolateDepth({320, 320}, pixels, depths, 20.0);
  for (int v = 120; v <= 180; ++v) {
    EXPECT_FALSE(std::isnan(depth(v, 112))) << v;  // inside a patch
    EXPECT_FALSE(std::isnan(depth(v, 196))) << v;
    for (int u = 125; u <= 183; ++u) ASSERT_TRUE(std::isnan(depth(v, u))) << u << ", " << v;
  }
  // The same points with a limit above the gap fill it.
  const cv::Mat1f bridged = InterpolateDepth({320, 320}, pixels, depths, 80.0);
  EXPECT_FALSE(std::isnan(bridged(150, 150)));
  // And one triangle whose longest edge (22.6 px) exceeds the limit leaves everything empty.
  const cv::Mat1f none =
      InterpolateDepth({64, 64}, {{10, 10}, {26, 10}, {10, 26}}, {100.0, 100.0, 100.0}, 20.0);
  EXPECT_EQ(cv::countNonZero(none == none), 0);  // NaN != NaN
}

}  // namespace
}  // namespace sewer3d
