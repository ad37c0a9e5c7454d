#include "sewer3d/pipeline/model_samples.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sewer3d/model/unroll.hpp"
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

void AddWallSamples(ModuleOffsetEstimator& estimator, const Centreline& centreline,
                    const std::vector<ModelAcquisition>& acquisitions,
                    const std::vector<std::vector<Eigen::Vector3d>>& samples) {
  double guess = centreline.station0_mm;
  for (std::size_t i = 0; i < acquisitions.size() && i < samples.size(); ++i) {
    const Eigen::Vector3d& centre = acquisitions[i].world_from_camera.translation;
    for (const Eigen::Vector3d& p : samples[i]) {
      const CylPoint cyl = Unroll(centreline, p, guess);
      guess = cyl.station_mm;
      const Eigen::Vector3d radial = centreline.FrameAt(cyl.station_mm).Direction(cyl.clock_rad);
      estimator.Add({acquisitions[i].module, cyl.station_mm, cyl.clock_rad, cyl.radius_mm,
                     std::abs((p - centre).normalized().dot(radial))});
    }
  }
}

namespace {

bool HasDepth(float z) { return std::isfinite(z) && z > 0.0f; }

/// Fills the runs of pixels without depth in one line of `depth_mm` (a row or a column: `at`
/// maps an index along it to the pixel) that have depth on both ends, by linear interpolation
/// into `holes` where it has none yet.
template <typename At>
void FillEnclosedRuns(int length, At&& at, const cv::Mat1f& depth_mm, cv::Mat1f& holes) {
  int last = -1;  // the last pixel with depth
  for (int i = 0; i < length; ++i) {
    const float z = depth_mm(at(i));
    if (!HasDepth(z)) continue;
    if (last >= 0 && i - last > 1) {
      const float z0 = depth_mm(at(last));
      for (int k = last + 1; k < i; ++k) {
        float& h = holes(at(k));
        if (!std::isfinite(h)) h = z0 + (z - z0) * static_cast<float>(k - last) / (i - last);
      }
    }
    last = i;
  }
}

}  // namespace

cv::Mat1f EnclosedHoleDepths(const cv::Mat1f& depth_mm) {
  cv::Mat1f holes(depth_mm.size(), std::numeric_limits<float>::quiet_NaN());
  for (int v = 0; v < depth_mm.rows; ++v)
    FillEnclosedRuns(
        depth_mm.cols, [v](int u) { return cv::Point(u, v); }, depth_mm, holes);
  for (int u = 0; u < depth_mm.cols; ++u)
    FillEnclosedRuns(
        depth_mm.rows, [u](int v) { return cv::Point(u, v); }, depth_mm, holes);
  return holes;
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
      if (!(HasDepth(z) && std::isfinite(xy[0]))) continue;
      // The module's range offset, along the ray: z shrinks by offset / |(x, y, 1)|.
      const double zc =
          z - weighting.range_offset_mm / std::sqrt(1.0 + xy[0] * xy[0] + xy[1] * xy[1]);
      const Eigen::Vector3d p = world_from_camera * Eigen::Vector3d(xy[0] * zc, xy[1] * zc, zc);
      const double weight = DepthWeight(z, weighting.depth_sigma_ref_mm, weighting.depth_ref_mm) *
                            BorderFeather(u, v, depth_mm.cols, depth_mm.rows, weighting.feather_px);
      const cv::Vec3b& c = color_bgr(v, u);
      if (maps.Add(p, cv::Vec3f(c[0], c[1], c[2]), weight)) ++added;
    }
  }
  if (!maps.CountsFrames()) return added;
  // The frame's own holes (lost spots, a gap's floor out of view): seen, not measured.
  const cv::Mat1f holes = EnclosedHoleDepths(depth_mm);
  for (int v = 0; v < depth_mm.rows; v += step) {
    for (int u = 0; u < depth_mm.cols; u += step) {
      const float z = holes(v, u);
      const cv::Vec2f& xy = normalised(v, u);
      if (!(std::isfinite(z) && std::isfinite(xy[0]))) continue;
      maps.AddSeen(world_from_camera * Eigen::Vector3d(xy[0] * z, xy[1] * z, z));
    }
  }
  return added;
}

}  // namespace sewer3d
