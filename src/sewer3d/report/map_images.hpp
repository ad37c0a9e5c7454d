#pragma once
/// \file
/// The report's pictures of the maps: the displacement as a heat map with a diverging colour
/// scale (inward blue, 0 white, outward red, no data dark grey), its range, and the CSS
/// gradient of the same scale for the colour bar.

#include <opencv2/core/mat.hpp>
#include <string>

namespace sewer3d {

/// The colour (BGR) of t ∈ [−1, 1] (clamped) on the diverging scale.
cv::Vec3b HeatColour(double t);

/// Colour per cell of `displacement_mm` / range_mm; NaN cells dark grey.
cv::Mat3b HeatImage(const cv::Mat1f& displacement_mm, double range_mm);

/// CSS linear-gradient (left = −range, right = +range) of the same scale.
std::string HeatGradientCss();

/// `image` turned so that station runs along x and clock down y (map rows become columns).
cv::Mat3b StationAlongX(const cv::Mat3b& image);

}  // namespace sewer3d
