#include "sewer3d/calib/chessboard.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

std::optional<std::vector<Eigen::Vector2d>> DetectChessboard(const cv::Mat& grey, int cols,
                                                             int rows) {
  SEWER3D_CHECK(grey.channels() == 1 && grey.depth() == CV_8U,
                "checkerboard detection needs an 8-bit grey image");
  // OpenCV's detector needs more than 2 corners a side, and an image where each square spans
  // a few pixels (smaller ones trip its adaptive threshold): no board is found in those.
  SEWER3D_VALIDATE(cols >= 3 && rows >= 3, "board",
                   "needs at least 3x3 inner corners, got " << cols << "x" << rows);
  if (grey.cols < 4 * (cols + 1) || grey.rows < 4 * (rows + 1)) return std::nullopt;
  std::vector<cv::Point2f> corners;
  if (!cv::findChessboardCorners(grey, cv::Size(cols, rows), corners,
                                 cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE)) {
    return std::nullopt;
  }
  // Sub-pixel window: as large as the squares allow (more edge pixels average more noise), a
  // sixth of the smallest corner spacing on each side, 11 x 11 px at least, 25 x 25 at most.
  double spacing = std::numeric_limits<double>::infinity();
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const cv::Point2f& p = corners[r * cols + c];
      if (c + 1 < cols)
        spacing = std::min(spacing, static_cast<double>(cv::norm(corners[r * cols + c + 1] - p)));
      if (r + 1 < rows)
        spacing = std::min(spacing, static_cast<double>(cv::norm(corners[(r + 1) * cols + c] - p)));
    }
  }
  const int half = std::clamp(static_cast<int>(std::lround(spacing / 6.0)), 5, 12);
  cv::cornerSubPix(grey, corners, cv::Size(half, half), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 0.001));
  std::vector<Eigen::Vector2d> out;
  for (const auto& p : corners) out.emplace_back(p.x, p.y);
  return out;
}

}  // namespace sewer3d
