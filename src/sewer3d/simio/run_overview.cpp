#include "sewer3d/simio/run_overview.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <string>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/sim/material.hpp"

namespace sewer3d {
namespace {

int SectionAt(const PipeGeometry& pipe, double station) {
  int i = 0;
  while (i + 1 < static_cast<int>(pipe.world().sections.size()) &&
         station >= pipe.SectionStartMm(i + 1))
    ++i;
  return i;
}

}  // namespace

cv::Mat3b RunOverview(const PipeGeometry& pipe, const Rig& rig, const Trajectory& trajectory,
                      const CapturePlan& plan, double mm_per_px, double range_mm) {
  // Station range: what the pattern images see.
  struct Dot {
    double station, clock;
    int module;
  };
  std::vector<Dot> dots;
  double lo = 1e18, hi = -1e18;
  for (const RunImage& shot : plan.shots) {
    if (shot.kind != ImageKind::kPattern) continue;
    const RigModule& m = rig.modules[shot.module];
    const Rigid3d world_from_camera =
        trajectory.WorldFromCarrier(shot.time_s) * m.carrier_from_camera;
    const CameraModel camera(m.module.camera);
    const int w = m.module.camera.width, h = m.module.camera.height, step = std::max(1, w / 160);
    for (int k = 0; k < 2 * (w + h); k += step) {
      const Eigen::Vector2d px = k < w           ? Eigen::Vector2d(k, 0)
                                 : k < w + h     ? Eigen::Vector2d(w - 1, k - w)
                                 : k < 2 * w + h ? Eigen::Vector2d(2 * w + h - 1 - k, h - 1)
                                                 : Eigen::Vector2d(0, 2 * (w + h) - 1 - k);
      const auto xy = camera.Unproject(px);
      if (!xy) continue;
      const auto hit =
          pipe.Intersect(world_from_camera.translation,
                         world_from_camera.rotation * Eigen::Vector3d(xy->x(), xy->y(), 1.0));
      if (!hit) continue;
      const PipeLocation at = pipe.Locate(hit->point);
      dots.push_back({at.station_mm, at.clock_rad, shot.module});
      lo = std::min(lo, at.station_mm);
      hi = std::max(hi, at.station_mm);
    }
  }
  if (dots.empty()) lo = 0.0, hi = pipe.world().LengthMm();
  lo = std::floor(lo / 100.0) * 100.0;
  hi = std::ceil(hi / 100.0) * 100.0;
  const double circumference = std::numbers::pi * pipe.world().sections.front().diameter_mm;
  const int width = static_cast<int>(std::ceil((hi - lo) / mm_per_px));
  const int height = static_cast<int>(std::ceil(circumference / mm_per_px));
  cv::Mat3b image(height, width);
  tbb::parallel_for(0, height, [&](int y) {
    const double clock = kTwoPi * (y + 0.5) / height;
    for (int x = 0; x < width; ++x) {
      const double station = lo + (x + 0.5) * mm_per_px;
      const int i = SectionAt(pipe, station);
      // Against the robot's smooth path, so that joint offsets show as steps.
      const Rigid3d frame = pipe.PathFrame(station);
      const auto hit = pipe.Intersect(frame.translation, frame.rotation * ClockDirection(clock));
      if (!hit) {
        image(y, x) = {0, 0, 0};
        continue;
      }
      const double radius = 0.5 * pipe.world().sections[i].diameter_mm;
      const double outward = (hit->point - frame.translation).norm() - radius;
      const Eigen::Vector3d albedo =
          MaterialAlbedo(hit->material, pipe.world().material_seed, hit->surface_mm);
      const double grey = std::clamp(0.35 + 0.9 * albedo.mean(), 0.0, 1.0);
      Eigen::Vector3d rgb = albedo / std::max(1e-6, albedo.mean()) * grey * 0.5 +
                            Eigen::Vector3d::Constant(0.5 * grey);
      const double tint = std::min(1.0, std::abs(outward) / range_mm);
      const Eigen::Vector3d towards =
          outward < 0 ? Eigen::Vector3d(1.0, 0.1, 0.05) : Eigen::Vector3d(0.1, 0.3, 1.0);
      if (std::abs(outward) > 0.2) rgb = (1.0 - tint) * rgb + tint * towards;
      rgb = (rgb * 255.0).cwiseMax(0.0).cwiseMin(255.0);
      image(y, x) = cv::Vec3b(static_cast<uchar>(rgb.z()), static_cast<uchar>(rgb.y()),
                              static_cast<uchar>(rgb.x()));
    }
  });
  const cv::Scalar grid(60, 60, 60);
  for (double s = lo; s <= hi; s += 100.0) {
    const int x = static_cast<int>((s - lo) / mm_per_px);
    cv::line(image, {x, 0}, {x, height - 1}, grid, 1);
    cv::putText(image, std::to_string(static_cast<int>(s)), {x + 2, 12}, cv::FONT_HERSHEY_PLAIN,
                0.8, {0, 0, 0}, 1);
  }
  for (int hour = 3; hour < 12; hour += 3) {
    const int y = height * hour / 12;
    cv::line(image, {0, y}, {width - 1, y}, grid, 1);
    cv::putText(image, std::to_string(hour) + " h", {2, y - 3}, cv::FONT_HERSHEY_PLAIN, 0.8,
                {0, 0, 0}, 1);
  }
  const cv::Vec3b colours[] = {{0, 200, 255}, {0, 255, 0},   {255, 0, 255},
                               {255, 255, 0}, {0, 128, 255}, {255, 128, 0}};
  for (const Dot& d : dots) {
    double clock = std::fmod(d.clock, kTwoPi);
    if (clock < 0) clock += kTwoPi;
    const int x = static_cast<int>((d.station - lo) / mm_per_px),
              y = static_cast<int>(clock / kTwoPi * height);
    if (x >= 0 && x < width && y >= 0 && y < height) image(y, x) = colours[d.module % 6];
  }
  return image;
}

}  // namespace sewer3d
