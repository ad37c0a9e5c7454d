#include "sewer3d/calib/chessboard.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

std::optional<std::vector<Eigen::Vector2d>> DetectChessboard(const cv::Mat& grey, int cols,
                                                             int rows) {
  SEWER3D_CHECK(grey.channels() == 1 && grey.depth() == CV_8U,
                "checkerboard detection needs an 8-bit grey image");
  SEWER3D_CHECK(cols >= 2 && rows >= 2, "board " << cols << "x" << rows);
  std::vector<cv::Point2f> corners;
  if (!cv::findChessboardCorners(grey, cv::Size(cols, rows), corners,
                                 cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE)) {
    return std::nullopt;
  }
  cv::cornerSubPix(grey, corners, cv::Size(5, 5), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 0.001));
  std::vector<Eigen::Vector2d> out;
  for (const auto& p : corners) out.emplace_back(p.x, p.y);
  return out;
}

}  // namespace sewer3d
