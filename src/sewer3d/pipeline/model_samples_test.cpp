#include "sewer3d/pipeline/model_samples.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace sewer3d {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// A wall sloping in depth (100 + u + 2v mm) with three holes: one inside the view (filled
// exactly, as the depth is linear), one reaching the left border along its rows but enclosed
// along its columns (filled from the columns), and the view's corner beyond the lit area
// (reaching the border both ways: left empty). Pixels with depth get no hole depth.
TEST(EnclosedHoleDepths, FillsTheFramesOwnHolesNotWhatLiesBeyondItsView) {
  cv::Mat1f depth(12, 16);
  for (int v = 0; v < depth.rows; ++v)
    for (int u = 0; u < depth.cols; ++u) depth(v, u) = 100.0f + u + 2.0f * v;
  depth(cv::Rect(5, 4, 4, 3)) = kNaN;   // inside
  depth(cv::Rect(0, 8, 3, 2)) = kNaN;   // at the left border, rows 8–9
  depth(cv::Rect(12, 0, 4, 2)) = kNaN;  // the top right corner
  const cv::Mat1f holes = EnclosedHoleDepths(depth);
  int filled = 0;
  for (int v = 0; v < depth.rows; ++v) {
    for (int u = 0; u < depth.cols; ++u) {
      if (!std::isfinite(holes(v, u))) continue;
      ++filled;
      EXPECT_FALSE(std::isfinite(depth(v, u))) << u << "," << v;
      EXPECT_NEAR(holes(v, u), 100.0f + u + 2.0f * v, 1e-4) << u << "," << v;
    }
  }
  EXPECT_EQ(filled, 4 * 3 + 3 * 2);
  EXPECT_FALSE(std::isfinite(holes(0, 15)));
  EXPECT_FALSE(std::isfinite(holes(1, 12)));
}

}  // namespace
}  // namespace sewer3d
