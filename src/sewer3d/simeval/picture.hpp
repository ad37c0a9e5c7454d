#pragma once
/// \file
/// Small drawing helpers shared by the evaluation pictures (error maps, residual images).

#include <opencv2/core.hpp>
#include <string>

namespace sewer3d {

/// Black text at `at` (its baseline's left end), OpenCV's plain font.
void DrawLabel(cv::Mat3b& image, const std::string& text, cv::Point at, double scale = 0.45);

/// A vertical colour bar of DisplacementView's colours, +range_mm at the top, −range_mm at the
/// bottom, `height` pixels tall and 20 wide from `top_left`, labelled on its right.
void DrawColourBar(cv::Mat3b& image, cv::Point top_left, int height, double range_mm);

}  // namespace sewer3d
