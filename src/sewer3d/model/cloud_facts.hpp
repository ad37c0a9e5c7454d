#pragma once
/// \file
/// What a camera-frame cloud tells about itself before a surface is fitted to it: how many points
/// lie behind the camera, how far it spans and how far it lies, and whether its coordinates look
/// like millimetres at all (`sewer3d evaluate plane|cylinder`).

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace sewer3d {

struct CameraCloudFacts {
  std::size_t points = 0;
  std::size_t behind = 0;           ///< points with z <= 0, which no module can see
  double extent_mm = 0.0;           ///< diagonal of the bounding box
  double median_distance_mm = 0.0;  ///< median distance of a point to the camera centre
};

/// The facts of `points` (camera frame, millimetres); all zero for an empty cloud.
CameraCloudFacts DescribeCameraCloud(const std::vector<Eigen::Vector3d>& points);

/// Why the coordinates are probably not millimetres, or empty. A wall seen by a module spans
/// tens of millimetres at a few hundred from the camera: a cloud under 5 mm across was most
/// likely written in metres, one nearer than 30 mm (median) in centimetres, one over 10 m away
/// in micrometres.
std::string CloudUnitsProblem(const CameraCloudFacts& facts);

}  // namespace sewer3d
