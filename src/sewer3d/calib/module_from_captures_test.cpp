// ModuleCalibrator's bookkeeping without a renderer: what a capture without a board, or with a
// board but no decodable pattern, reports; misuse throws.

#include "sewer3d/calib/module_from_captures.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

// A fronto-parallel 9 x 6 board drawn straight into the image: 40 px squares.
cv::Mat1b DrawnBoard() {
  cv::Mat1b image(486, 648, std::uint8_t{230});
  for (int i = 0; i < 7; ++i) {
    for (int j = 0; j < 10; ++j) {
      if ((i + j) % 2 == 0) {
        cv::rectangle(image, cv::Rect(124 + 40 * j, 103 + 40 * i, 40, 40), cv::Scalar(20),
                      cv::FILLED);
      }
    }
  }
  return image;
}

TEST(ModuleCalibrator, ReportsWhatBecameOfEachCapture) {
  ModuleCalibrator calibrator(testing::SmallDefaultModule(648), DefaultPatternArray(),
                              PatternConstraints{}, BoardLayout{});
  const cv::Mat1b dark(486, 648, std::uint8_t{10});
  const CaptureOutcome blank = calibrator.AddCapture(cv::Mat1b(486, 648, std::uint8_t{128}), dark);
  EXPECT_EQ(blank.status, CaptureOutcome::Status::kBoardNotFound);
  EXPECT_EQ(blank.corners, 0);
  // The board is there, the pattern image is dark: no corner can be carried.
  const CaptureOutcome unlit = calibrator.AddCapture(DrawnBoard(), dark);
  EXPECT_EQ(unlit.status, CaptureOutcome::Status::kCornersNotCarried);
  EXPECT_EQ(unlit.corners, 54);
  EXPECT_EQ(unlit.corners_missing, 54);
  EXPECT_EQ(unlit.spots_decoded, 0);
  EXPECT_EQ(calibrator.captures_used(), 0);
  EXPECT_THROW(calibrator.Calibrate(), std::invalid_argument);  // needs 3 captures used
}

TEST(ModuleCalibrator, RejectsMisuse) {
  const ModuleDescription module = testing::SmallDefaultModule(648);
  BoardLayout one_row;
  one_row.rows = 1;
  EXPECT_THROW(ModuleCalibrator(module, DefaultPatternArray(), PatternConstraints{}, one_row),
               std::invalid_argument);
  ModuleCalibratorOptions preset_models;
  preset_models.corner_transfer.camera = module.camera;
  preset_models.corner_transfer.projector = module.projector;
  EXPECT_THROW(ModuleCalibrator(module, DefaultPatternArray(), PatternConstraints{}, BoardLayout{},
                                preset_models),
               std::invalid_argument);
  ModuleCalibrator calibrator(module, DefaultPatternArray(), PatternConstraints{}, BoardLayout{});
  EXPECT_THROW(calibrator.AddCapture(cv::Mat1b(480, 640), cv::Mat1b(486, 648)),
               std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
