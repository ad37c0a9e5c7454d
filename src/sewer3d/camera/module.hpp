#pragma once
/// \file
/// Description of one structured-light module: camera, projector (an inverse camera), their
/// extrinsics and the projected spot pattern (DESIGN.md, module contract). Plain data and
/// geometry only; reading and writing module.json lives in io/.

#include <Eigen/Core>
#include <string>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/rigid3.hpp"

namespace sewer3d {

/// How the pattern array is laid over the projector image.
struct PatternLayout {
  std::string matrix_path = "pattern.png";  ///< PNG, relative to the module file
  double pitch_px = 8.0;                    ///< element pitch, projector px
  double spot_diameter_px = 4.0;            ///< disk diameter, projector px
  Eigen::Vector2d offset_px = Eigen::Vector2d::Zero();

  /// Centre (projector px) of element (r, c) of the tiling:
  /// u = offset_u + (c + 0.5) pitch - 0.5, v = offset_v + (r + 0.5) pitch - 0.5.
  Eigen::Vector2d ElementCentre(int r, int c) const {
    return {offset_px.x() + (c + 0.5) * pitch_px - 0.5, offset_px.y() + (r + 0.5) * pitch_px - 0.5};
  }
  void Check() const;
};

struct ModuleDescription {
  /// Accepted baseline (projector centre to camera centre), mm; the paper's is 77.6 mm.
  static constexpr double kMinBaselineMm = 1.0, kMaxBaselineMm = 1000.0;
  CameraIntrinsics camera;
  CameraIntrinsics projector;
  /// X_projector = R X_camera + t (mm).
  Rigid3d projector_from_camera;
  PatternLayout pattern;
  /// The module file's JSON text as read, so that fields this version does not know survive a
  /// rewrite. Empty for modules built in code.
  std::string source_json;

  void Check() const;
};

/// Displacement of the projected point, in projector pixels, when the surface point seen by
/// a camera pixel moves from depth z_min to z_max (mm along the camera's optical axis).
struct DisparityRange {
  double max_du_px = 0.0;  ///< largest |Δu| over the image
  double max_dv_px = 0.0;  ///< largest |Δv| over the image
  double max_cols = 0.0;   ///< max_du_px / pitch: columns the array must distinguish
  double max_rows = 0.0;   ///< max_dv_px / pitch
};

/// Scans the camera image (every `step_px` pixels) for the disparity range of the module.
/// Pixels whose ray cannot be unprojected, or whose points fall behind the projector, are
/// skipped.
DisparityRange ComputeDisparityRange(const ModuleDescription& module, double z_min_mm,
                                     double z_max_mm, int step_px = 16);

/// Why a pattern matrix of `rows` x `cols` cannot be decoded over a module's disparity `range`
/// (ComputeDisparityRange over the working distances): its windows are unique along a row and the
/// tile repeats, so the disparity must stay within the columns, and a disparity mostly along v
/// within the rows. Empty when it can.
std::string PatternSpanProblem(const DisparityRange& range, int rows, int cols);

}  // namespace sewer3d
