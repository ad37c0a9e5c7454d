#include "sewer3d/sim/spot_truth.hpp"

#include <cmath>

namespace sewer3d {
namespace {

// Calls visit(r, c, hit) for each tiled element (of the whole spots, or of any lit part) whose
// centre's projector ray meets the surface.
template <typename Visit>
void ForEachLitElement(const ModuleDescription& module, const BinaryArray& pattern,
                       const Surface& surface, bool whole_spots_only, Visit&& visit) {
  const CameraModel projector(module.projector);
  const Rigid3d camera_from_projector = module.projector_from_camera.Inverse();
  const double pitch = module.pattern.pitch_px;
  const int rows = static_cast<int>(std::ceil(module.projector.height / pitch));
  const int cols = static_cast<int>(std::ceil(module.projector.width / pitch));
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
      const auto hit = surface.Intersect(camera_from_projector.translation,
                                         camera_from_projector.rotation * *ray);
      if (hit) visit(r, c, *hit);
    }
  }
}

}  // namespace

std::vector<Eigen::Vector2d> ProjectedSpotCentres(const ModuleDescription& module,
                                                  const BinaryArray& pattern, const Scene& scene,
                                                  bool whole_spots_only) {
  const CameraModel camera(module.camera);
  std::vector<Eigen::Vector2d> pixels;
  ForEachLitElement(module, pattern, SceneSurface(scene), whole_spots_only,
                    [&](int, int, const SurfaceHit& hit) {
                      if (const auto pixel = camera.Project(hit.point)) pixels.push_back(*pixel);
                    });
  return pixels;
}

std::vector<VisibleSpot> VisibleSpots(const ModuleDescription& module, const BinaryArray& pattern,
                                      const Surface& surface, double margin_px,
                                      double occlusion_tolerance_mm) {
  const CameraModel camera(module.camera);
  std::vector<VisibleSpot> spots;
  ForEachLitElement(module, pattern, surface, true, [&](int r, int c, const SurfaceHit& hit) {
    const auto pixel = camera.Project(hit.point);
    if (!pixel || pixel->x() < margin_px - 0.5 || pixel->y() < margin_px - 0.5 ||
        pixel->x() > module.camera.width - 0.5 - margin_px ||
        pixel->y() > module.camera.height - 0.5 - margin_px) {
      return;
    }
    const auto seen = surface.Intersect(Eigen::Vector3d::Zero(), hit.point);
    if (!seen || (seen->point - hit.point).norm() > occlusion_tolerance_mm) return;
    spots.push_back({r, c, *pixel, hit});
  });
  return spots;
}

}  // namespace sewer3d
