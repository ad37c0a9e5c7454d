// Rendered checkerboard captures of a module with known intrinsics (realistic noise).

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "sewer3d/calib/camera_calibration.hpp"
#include "sewer3d/calib/chessboard.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/sim/board.hpp"
#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

TEST(CameraCalibration, RecoversTheTrueCameraFromRenderedBoards) {
  const ModuleDescription module = testing::SmallDefaultModule(1296);
  Checkerboard board;
  const auto poses = RandomBoardPoses(module, board, 10, 3);
  std::vector<CalibrationView> views;
  for (size_t i = 0; i < poses.size(); ++i) {
    RenderOptions o;
    o.supersampling = 2;  // one sample per pixel leaves the square edges aliased
    o.images = RenderImages::kTexture;
    o.truth_depth = false;
    o.seed = 10 + i;
    const RenderedFrame frame =
        RenderFrame(module, DefaultPatternArray(), BoardSurface(board, poses[i]), o);
    cv::Mat grey;
    cv::Mat rgb8;
    frame.texture.convertTo(rgb8, CV_8U);
    cv::cvtColor(rgb8, grey, cv::COLOR_RGB2GRAY);
    const auto corners = DetectChessboard(grey, board.cols, board.rows);
    ASSERT_TRUE(corners.has_value()) << "pose " << i;
    views.push_back({*corners});
  }
  const CalibrationResult r =
      CalibrateCamera(views, BoardCorners(board.cols, board.rows, board.square_mm),
                      module.camera.width, module.camera.height);
  const CameraIntrinsics& c = r.intrinsics;
  std::printf(
      "true fx %.3f cx %.3f cy %.3f k1 %.4f; calibrated fx %.3f fy %.3f cx %.3f cy %.3f k1 %.4f, "
      "RMS %.3f px\n",
      module.camera.fx, module.camera.cx, module.camera.cy, module.camera.k[0], c.fx, c.fy, c.cx,
      c.cy, c.k[0], r.rms_px);
  // Bounds: a few standard deviations of the estimate (sigma printed by the CLI: ~0.05 %).
  EXPECT_NEAR(c.fx / module.camera.fx, 1.0, 2e-3);
  EXPECT_NEAR(c.fy / module.camera.fy, 1.0, 2e-3);
  EXPECT_NEAR(c.cx, module.camera.cx, 1.5);
  EXPECT_NEAR(c.cy, module.camera.cy, 1.5);
  EXPECT_NEAR(c.k[0], module.camera.k[0], 0.01);
  EXPECT_LT(r.rms_px, 0.3);
  // The poses are recovered too.
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_LT((r.camera_from_board[i].translation - poses[i].translation).norm(),
              0.01 * poses[i].translation.norm());
  }
}

}  // namespace
}  // namespace sewer3d
