#pragma once
/// \file
/// How much a camera sees: the full field of view through its principal point.

#include "sewer3d/camera/camera_model.hpp"

namespace sewer3d {

/// Full field of view (deg) along x (`horizontal`) or y through the principal point, from image
/// edge to image edge; NaN when an edge cannot be unprojected (the lens model folds over).
double FieldOfViewDeg(const CameraModel& model, bool horizontal);

/// A camera that sees less than this (deg, either axis) is no inspection camera: its lens model
/// squeezes the image to nothing (camera k1 = 1e10 gives 0.0 deg).
inline constexpr double kMinFieldOfViewDeg = 1.0;

}  // namespace sewer3d
