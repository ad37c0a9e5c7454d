#include "sewer3d/pipeline/model_samples.hpp"

#include <algorithm>
#include <cmath>

#include "sewer3d/register/depth_geometry.hpp"

namespace sewer3d {

std::vector<Eigen::Vector3d> FitSamples(const cv::Mat1f& depth_mm, const CameraModel& camera,
                                        const Rigid3d& world_from_camera, int target) {
  const double pixels = static_cast<double>(depth_mm.rows) * depth_mm.cols;
  const int step = std::max(1, static_cast<int>(std::sqrt(pixels / std::max(target, 1))));
  std::vector<Eigen::Vector3d> out = SampleDepthPoints(depth_mm, camera, step);
  for (Eigen::Vector3d& p : out) p = world_from_camera * p;
  return out;
}

long long AddAcquisitionPixels(MapAccumulator& maps, const cv::Mat1f& depth_mm,
                               const cv::Mat3b& color_bgr, const cv::Mat2f& normalised,
                               const Rigid3d& world_from_camera, const PixelWeighting& weighting) {
  maps.BeginFrame();
  long long added = 0;
  const int step = std::max(1, weighting.pixel_step);
  for (int v = 0; v < depth_mm.rows; v += step) {
    for (int u = 0; u < depth_mm.cols; u += step) {
      const float z = depth_mm(v, u);
      const cv::Vec2f& xy = normalised(v, u);
      if (!(std::isfinite(z) && z > 0.0f && std::isfinite(xy[0]))) continue;
      const Eigen::Vector3d p = world_from_camera * Eigen::Vector3d(xy[0] * z, xy[1] * z, z);
      const double weight = DepthWeight(z, weighting.depth_sigma_ref_mm, weighting.depth_ref_mm) *
                            BorderFeather(u, v, depth_mm.cols, depth_mm.rows, weighting.feather_px);
      const cv::Vec3b& c = color_bgr(v, u);
      if (maps.Add(p, cv::Vec3f(c[0], c[1], c[2]), weight)) ++added;
    }
  }
  return added;
}

}  // namespace sewer3d
