#include "sewer3d/sim/spot_truth.hpp"

#include <cmath>

namespace sewer3d {

std::vector<Eigen::Vector2d> ProjectedSpotCentres(const ModuleDescription& module,
                                                  const BinaryArray& pattern, const Scene& scene,
                                                  bool whole_spots_only) {
  const CameraModel camera(module.camera), projector(module.projector);
  const Rigid3d camera_from_projector = module.projector_from_camera.Inverse();
  const double pitch = module.pattern.pitch_px;
  const int rows = static_cast<int>(std::ceil(module.projector.height / pitch));
  const int cols = static_cast<int>(std::ceil(module.projector.width / pitch));
  std::vector<Eigen::Vector2d> pixels;
  for (int r = -1; r <= rows; ++r) {
    for (int c = -1; c <= cols; ++c) {
      if (!pattern.tiled(r, c)) continue;
      // Disk radius plus a pixel for the optics' blur; inward for whole spots, outward for any
      // lit part.
      const Eigen::Vector2d centre = module.pattern.ElementCentre(r, c);
      const double reach = 0.5 * module.pattern.spot_diameter_px + 1.0;
      const double a = whole_spots_only ? reach : -reach;
      if (centre.x() - a < -0.5 || centre.y() - a < -0.5 ||
          centre.x() + a > module.projector.width - 0.5 ||
          centre.y() + a > module.projector.height - 0.5) {
        continue;
      }
      const auto ray = projector.Ray(centre);
      if (!ray) continue;
      const auto hit = Intersect(scene, camera_from_projector.translation,
                                 camera_from_projector.rotation * *ray);
      if (!hit) continue;
      if (const auto pixel = camera.Project(hit->point)) pixels.push_back(*pixel);
    }
  }
  return pixels;
}

}  // namespace sewer3d
