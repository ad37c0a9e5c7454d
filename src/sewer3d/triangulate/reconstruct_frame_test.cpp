// FrameReconstructor's contract without a renderer: a frame where nothing decodes is a result
// with zero points, misuse throws.

#include "sewer3d/triangulate/reconstruct_frame.hpp"

#include <gtest/gtest.h>

#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

TEST(FrameReconstructor, NothingDecodedIsAnEmptyResult) {
  const ModuleDescription module = testing::SmallDefaultModule(648);
  FrameReconstructor reconstructor(module, DefaultPatternArray(), PatternConstraints{});
  const cv::Mat3b texture(486, 648, cv::Vec3b(10, 20, 30));
  for (const cv::Mat& image : {cv::Mat(cv::Mat1b(486, 648, std::uint8_t{40})),
                               cv::Mat(cv::Mat1w(486, 648, std::uint16_t{1000}))}) {
    const FrameReconstruction frame = reconstructor.Reconstruct(image, &texture);
    EXPECT_TRUE(frame.points.empty());
    EXPECT_TRUE(frame.coloured);
    EXPECT_EQ(frame.report.spots_found, 0);
    EXPECT_EQ(frame.report.points, 0);
    ASSERT_EQ(frame.depth_mm.size(), cv::Size(648, 486));
    EXPECT_EQ(cv::countNonZero(frame.depth_mm == frame.depth_mm), 0);  // all NaN
  }
}

TEST(FrameReconstructor, RejectsMisuse) {
  const ModuleDescription module = testing::SmallDefaultModule(648);
  FrameReconstructionOptions options;
  options.max_edge_steps = 0.0;
  EXPECT_THROW(FrameReconstructor(module, DefaultPatternArray(), PatternConstraints{}, options),
               std::invalid_argument);
  FrameReconstructor reconstructor(module, DefaultPatternArray(), PatternConstraints{});
  EXPECT_THROW(reconstructor.Reconstruct(cv::Mat1f(486, 648, 0.0f)), std::invalid_argument);
  EXPECT_THROW(reconstructor.Reconstruct(cv::Mat1b(480, 640, std::uint8_t{0})),
               std::invalid_argument);
  const cv::Mat3b small_texture(10, 10);
  EXPECT_THROW(reconstructor.Reconstruct(cv::Mat1b(486, 648, std::uint8_t{0}), &small_texture),
               std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
