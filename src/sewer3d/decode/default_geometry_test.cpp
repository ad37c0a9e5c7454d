// The default module and the shipped pattern together: a decoded window names an element only
// modulo the array, so the array must be wider than the disparity range of the module.

#include <gtest/gtest.h>

#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/pattern/default_pattern.hpp"

namespace sewer3d {
namespace {

TEST(DefaultGeometry, ShippedPatternSpansTheDisparityRange) {
  const ModuleDescription m = MakeDefaultModule({});
  const DisparityRange range =
      ComputeDisparityRange(m, kWorkingDistanceMinMm, kWorkingDistanceMaxMm, 8);
  // f b (1/75 - 1/225) / pitch at the image centre row; distortion adds a little elsewhere.
  EXPECT_GT(range.max_cols, 140.0);
  EXPECT_LT(range.max_cols, 170.0);
  const BinaryArray array = DefaultPatternArray();
  EXPECT_GT(array.cols, range.max_cols + 6);  // unique along the epipolar line, with margin
}

}  // namespace
}  // namespace sewer3d
