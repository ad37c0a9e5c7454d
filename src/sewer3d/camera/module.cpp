#include "sewer3d/camera/module.hpp"

#include <algorithm>
#include <cmath>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

void PatternLayout::Check() const {
  SEWER3D_CHECK(!matrix_path.empty(), "pattern matrix path is empty");
  SEWER3D_CHECK(std::isfinite(pitch_px) && pitch_px > 0.0, "pitch_px " << pitch_px);
  SEWER3D_CHECK(
      std::isfinite(spot_diameter_px) && spot_diameter_px > 0.0 && spot_diameter_px <= pitch_px,
      "spot_diameter_px " << spot_diameter_px << " with pitch " << pitch_px);
  SEWER3D_CHECK(offset_px.allFinite(), "offset_px");
}

void ModuleDescription::Check() const {
  camera.Check();
  projector.Check();
  pattern.Check();
  SEWER3D_CHECK(projector_from_camera.translation.allFinite(), "translation");
  SEWER3D_CHECK(std::abs(projector_from_camera.rotation.norm() - 1.0) < 1e-9, "rotation");
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

}  // namespace sewer3d
