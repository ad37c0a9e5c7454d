// Camera calibration on OpenCV's real sample chessboard images (tests/data/opencv-chessboard),
// against OpenCV's calibrateCamera on the same corners and model.

#include "sewer3d/calib/camera_calibration.hpp"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "sewer3d/calib/chessboard.hpp"

namespace sewer3d {
namespace {

std::vector<CalibrationView> DetectAll() {
  std::vector<CalibrationView> views;
  for (const char* name :
       {"01", "02", "03", "04", "05", "06", "07", "08", "09", "11", "12", "13", "14"}) {
    const std::string path =
        std::string(SEWER3D_TEST_DATA_DIR) + "/opencv-chessboard/left" + name + ".jpg";
    const cv::Mat grey = cv::imread(path, cv::IMREAD_GRAYSCALE);
    EXPECT_FALSE(grey.empty()) << path;
    const auto corners = DetectChessboard(grey, 9, 6);
    EXPECT_TRUE(corners.has_value()) << path;
    if (corners) views.push_back({*corners});
  }
  return views;
}

TEST(CameraCalibration, AgreesWithOpenCvOnRealImages) {
  const std::vector<CalibrationView> views = DetectAll();
  ASSERT_EQ(views.size(), 13u);
  const auto board = BoardCorners(9, 6, 1.0);
  const CalibrationResult ours = CalibrateCamera(views, board, 640, 480);
  // OpenCV on the same corners and model (k1, k2, k3; no tangential terms).
  std::vector<std::vector<cv::Point3f>> object(views.size());
  std::vector<std::vector<cv::Point2f>> image(views.size());
  for (size_t v = 0; v < views.size(); ++v) {
    for (size_t i = 0; i < board.size(); ++i) {
      object[v].emplace_back(board[i].x(), board[i].y(), 0.0f);
      image[v].emplace_back(views[v].corners_px[i].x(), views[v].corners_px[i].y());
    }
  }
  cv::Mat k, d;
  std::vector<cv::Mat> rvecs, tvecs;
  const double cv_rms = cv::calibrateCamera(
      object, image, {640, 480}, k, d, rvecs, tvecs, cv::CALIB_ZERO_TANGENT_DIST,
      cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 200, 1e-12));
  std::printf(
      "ours:   fx %.3f fy %.3f cx %.3f cy %.3f k (%.5f %.5f %.5f) RMS %.4f px (sigma fx %.3f cx "
      "%.3f)\n",
      ours.intrinsics.fx, ours.intrinsics.fy, ours.intrinsics.cx, ours.intrinsics.cy,
      ours.intrinsics.k[0], ours.intrinsics.k[1], ours.intrinsics.k[2], ours.rms_px, ours.sigma[0],
      ours.sigma[2]);
  std::printf("OpenCV: fx %.3f fy %.3f cx %.3f cy %.3f k (%.5f %.5f %.5f) RMS %.4f px\n",
              k.at<double>(0, 0), k.at<double>(1, 1), k.at<double>(0, 2), k.at<double>(1, 2),
              d.at<double>(0), d.at<double>(1), d.at<double>(4), cv_rms);
  EXPECT_TRUE(ours.converged);
  EXPECT_NEAR(ours.intrinsics.fx / k.at<double>(0, 0), 1.0, 1e-3);
  EXPECT_NEAR(ours.intrinsics.fy / k.at<double>(1, 1), 1.0, 1e-3);
  EXPECT_NEAR(ours.rms_px / cv_rms, 1.0, 1e-3);
  EXPECT_NEAR(ours.intrinsics.cx, k.at<double>(0, 2), 0.5);
  EXPECT_NEAR(ours.intrinsics.cy, k.at<double>(1, 2), 0.5);
  // The published reference for this detector (README): fx 532.9, RMS 0.204 px.
  EXPECT_NEAR(ours.intrinsics.fx, 532.9, 1.0);
  EXPECT_NEAR(ours.rms_px, 0.204, 0.01);
  // Per-view RMS and residuals are consistent with the total.
  double sum = 0.0;
  for (double r : ours.view_rms_px) sum += r * r * board.size();
  EXPECT_NEAR(std::sqrt(sum / (board.size() * views.size())), ours.rms_px, 1e-9);
  EXPECT_GT(ours.sigma[0], 0.0);
  EXPECT_LT(ours.sigma[0], 5.0);
}

TEST(CameraCalibration, RejectsTooFewViews) {
  std::vector<CalibrationView> views(2);
  EXPECT_THROW(CalibrateCamera(views, BoardCorners(9, 6, 1.0), 640, 480), std::invalid_argument);
}

TEST(Chessboard, ReportsABoardThatIsNotThere) {
  const cv::Mat blank(480, 640, CV_8U, cv::Scalar(128));
  EXPECT_FALSE(DetectChessboard(blank, 9, 6).has_value());
}

}  // namespace
}  // namespace sewer3d
