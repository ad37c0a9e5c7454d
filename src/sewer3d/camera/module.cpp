#include "sewer3d/camera/module.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/camera/field_of_view.hpp"
#include "sewer3d/core/check.hpp"

namespace sewer3d {

void PatternLayout::Check() const {
  // Field names as in module.json's "pattern".
  SEWER3D_VALIDATE(!matrix_path.empty(), "matrix", "must name the pattern's PNG");
  SEWER3D_VALIDATE(std::isfinite(pitch_px) && pitch_px > 0.0, "pitch_px",
                   "must be finite and > 0, got " << pitch_px);
  SEWER3D_VALIDATE(
      std::isfinite(spot_diameter_px) && spot_diameter_px > 0.0 && spot_diameter_px <= pitch_px,
      "spot_diameter_px",
      "must be > 0 and at most pitch_px (" << pitch_px << "), got " << spot_diameter_px);
  SEWER3D_VALIDATE(offset_px.allFinite(), "offset_px", "must be finite");
}

void ModuleDescription::Check() const {
  CheckWithin("camera.", [&] { camera.Check(); });
  CheckWithin("projector.", [&] { projector.Check(); });
  CheckWithin("pattern.", [&] { pattern.Check(); });
  SEWER3D_VALIDATE(projector_from_camera.translation.allFinite(),
                   "projector_from_camera.translation_mm", "must be finite");
  // Triangulation needs a baseline; one beyond a metre is no inspection module (and makes the
  // disparity search unbounded).
  const double baseline = projector_from_camera.translation.norm();
  SEWER3D_VALIDATE(baseline >= kMinBaselineMm && baseline <= kMaxBaselineMm,
                   "projector_from_camera.translation_mm",
                   "the baseline is " << baseline << " mm; allowed " << kMinBaselineMm << ".."
                                      << kMaxBaselineMm << " mm");
  SEWER3D_VALIDATE(
      pattern.pitch_px >= 1.0 && pattern.pitch_px <= std::min(projector.width, projector.height),
      "pattern.pitch_px",
      "must be between 1 px and the projector's size, got " << pattern.pitch_px);
  const CameraModel model(camera);
  const double fov_x = FieldOfViewDeg(model, true), fov_y = FieldOfViewDeg(model, false);
  SEWER3D_VALIDATE(!(fov_x < kMinFieldOfViewDeg || fov_y < kMinFieldOfViewDeg), "camera.k",
                   "the camera sees " << fov_x << " x " << fov_y << " deg (under "
                                      << kMinFieldOfViewDeg
                                      << " deg): its distortion or focal length leaves no view");
  // The grid's offset shifts the spots within the projector image; beyond its size no spot of
  // the grid is left on the projector (and a huge offset makes the tile search unbounded).
  SEWER3D_VALIDATE(std::abs(pattern.offset_px.x()) <= projector.width &&
                       std::abs(pattern.offset_px.y()) <= projector.height,
                   "pattern.offset_px",
                   "must lie within the projector's size (±"
                       << projector.width << ", ±" << projector.height << " px), got ("
                       << pattern.offset_px.x() << ", " << pattern.offset_px.y() << ")");
  SEWER3D_VALIDATE(std::abs(projector_from_camera.rotation.norm() - 1.0) < 1e-9,
                   "projector_from_camera.rotation", "must be a rotation");
  // The camera must resolve the spots: a pattern pitch imaged on a fraction of a pixel leaves
  // nothing to decode (and would have the renderer sample many projector pixels per pixel).
  constexpr double kMinPitchInCameraPx = 0.25;
  const double pitch_in_camera = pattern.pitch_px * camera.fx / projector.fx;
  SEWER3D_VALIDATE(pitch_in_camera >= kMinPitchInCameraPx, "camera.fx",
                   "the pattern pitch of " << pattern.pitch_px << " projector px spans "
                                           << pitch_in_camera << " camera px (under "
                                           << kMinPitchInCameraPx
                                           << "): the camera cannot resolve the spots");
  // Depth comes from disparity: a projector on the camera's line of sight, or one turned away
  // from what the camera sees, measures none.
  const int step = std::max(1, std::max(camera.width, camera.height) / 64);
  const DisparityRange range =
      ComputeDisparityRange(*this, kWorkingDistanceMinMm, kWorkingDistanceMaxMm, step);
  SEWER3D_VALIDATE(range.max_du_px + range.max_dv_px >= 1.0, "projector_from_camera",
                   "walls " << kWorkingDistanceMinMm << "-" << kWorkingDistanceMaxMm
                            << " mm from the camera shift the pattern by "
                            << range.max_du_px + range.max_dv_px
                            << " px (under 1 px): the projector lies on the camera's line of "
                               "sight or faces away from its view, so no depth can be measured");
}

DisparityRange ComputeDisparityRange(const ModuleDescription& module, double z_min_mm,
                                     double z_max_mm, int step_px) {
  SEWER3D_CHECK(z_min_mm > 0.0 && z_max_mm > z_min_mm, z_min_mm << ".." << z_max_mm);
  SEWER3D_CHECK(step_px > 0);
  const CameraModel camera(module.camera);
  const CameraModel projector(module.projector);
  DisparityRange range;
  for (int v = 0; v < module.camera.height; v += step_px) {
    for (int u = 0; u < module.camera.width; u += step_px) {
      const auto xy = camera.Unproject({double(u), double(v)});
      if (!xy) continue;
      const Eigen::Vector3d ray(xy->x(), xy->y(), 1.0);
      const auto near = projector.Project(module.projector_from_camera * (ray * z_min_mm));
      const auto far = projector.Project(module.projector_from_camera * (ray * z_max_mm));
      if (!near || !far) continue;
      range.max_du_px = std::max(range.max_du_px, std::abs(near->x() - far->x()));
      range.max_dv_px = std::max(range.max_dv_px, std::abs(near->y() - far->y()));
    }
  }
  range.max_cols = range.max_du_px / module.pattern.pitch_px;
  range.max_rows = range.max_dv_px / module.pattern.pitch_px;
  return range;
}

std::string PatternSpanProblem(const DisparityRange& range, int rows, int cols) {
  std::ostringstream problem;
  if (cols <= range.max_cols) {
    problem << "the pattern's " << cols << " columns do not cover the "
            << static_cast<int>(std::ceil(range.max_cols)) << " the disparity range needs";
  } else if (range.max_dv_px > range.max_du_px && rows <= range.max_rows) {
    // Lens distortion tilts a full-size module's lines by a few degrees (58 px along v against
    // 1185 along u), which the decoder follows; a disparity mostly along v meets a twin.
    problem.precision(3);
    problem << "the disparity runs " << range.max_rows
            << " rows along the projector's v, and the pattern repeats every " << rows
            << " rows: a window meets its twin on the same epipolar line (the baseline must lie "
               "along the pattern's rows, projector u)";
  }
  return problem.str();
}

}  // namespace sewer3d
