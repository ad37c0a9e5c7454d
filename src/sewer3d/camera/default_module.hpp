#pragma once
/// \file
/// The paper's module geometry as a default (derivation in docs/default_module.md).
///
/// Frames: camera x right (around the pipe), y down (along the carrier axis), z radially
/// outward. The projector sits on the carrier axis at +b along camera y, optical axis parallel
/// to the camera's, and is rolled by 90° about it so that its image rows run along the
/// baseline: epipolar lines are projector rows and the pattern array's long side (its
/// columns) spans the disparity. Both sensors are shifted so that the centres of the two fields
/// meet at the middle of the working range with the paper's stereo angle.

#include <array>
#include <string>

#include "sewer3d/camera/module.hpp"

namespace sewer3d {

/// Camera-to-wall distances (along the optical axis) the module must cover: walls 100-200 mm
/// from the carrier axis (DN200-DN400) with up to 25 mm decentring.
inline constexpr double kWorkingDistanceMinMm = 75.0;
inline constexpr double kWorkingDistanceMaxMm = 225.0;

struct DefaultModuleOptions {
  int camera_width = 2592;
  int camera_height = 1944;
  double horizontal_fov_deg = 76.0;            ///< full horizontal field, distortion included
  double stereo_angle_deg = 29.0;              ///< angle between the field centres where they meet
  double meeting_distance_mm = 150.0;          ///< middle of the working range
  std::array<double, 3> k{-0.08, 0.015, 0.0};  ///< same lens on camera and projector
  double pitch_px = 8.0;
  double spot_diameter_px = 4.0;
  std::string matrix_path = "pattern.png";

  void Check() const;
};

/// Derived quantities, for reports and docs.
struct DefaultModuleGeometry {
  double focal_px = 0.0;
  double baseline_mm = 0.0;
  double field_tilt_deg = 0.0;         ///< each field's centre is tilted this much toward the other
  double lens_vertical_fov_deg = 0.0;  ///< vertical field of the lens on an unshifted sensor
  double field_top_deg = 0.0;          ///< angle of the top image edge from the optical axis (< 0)
  double field_bottom_deg = 0.0;       ///< angle of the bottom image edge from the optical axis
};

ModuleDescription MakeDefaultModule(const DefaultModuleOptions& options);
DefaultModuleGeometry DescribeDefaultModule(const DefaultModuleOptions& options);

}  // namespace sewer3d
