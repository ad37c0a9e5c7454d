#include "sewer3d/camera/module_checks.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/camera/default_module.hpp"

namespace sewer3d {

double DepthErrorMm(const ModuleDescription& m, double z_mm) {
  const Eigen::Vector3d c = m.projector_from_camera.Inverse().translation;
  const double baseline = std::hypot(c.x(), c.y());  // across the view: what triangulates
  const double f = std::min(m.camera.fx, m.camera.fy);
  return baseline > 0.0 ? z_mm * z_mm * kDisparityErrorPx / (f * baseline) : HUGE_VAL;
}

std::string DepthPrecisionProblem(const ModuleDescription& m) {
  constexpr double kMaxDepthErrorMm = 1.0;
  const double error = DepthErrorMm(m, kWorkingDistanceMaxMm);
  if (error <= kMaxDepthErrorMm) return "";
  return fmt::format(
      "depth error ±{:.1f} mm at {:g} mm for {:g} px of disparity error (baseline {:.1f} mm "
      "across the view), more than {:g} mm: the wall would be measured too coarsely; choose a "
      "larger stereo angle (a longer baseline)",
      error, kWorkingDistanceMaxMm, kDisparityErrorPx,
      std::hypot(m.projector_from_camera.Inverse().translation.x(),
                 m.projector_from_camera.Inverse().translation.y()),
      kMaxDepthErrorMm);
}

std::string SpotSizeProblem(const ModuleDescription& m) {
  constexpr double kMinSpotPx = 1.5, kMinPitchPx = 3.0;
  // Camera pixels per projector pixel on a wall at the working distance (the centres are
  // millimetres apart, the wall a hundred away).
  const double scale =
      std::min(m.camera.fx, m.camera.fy) / std::max(m.projector.fx, m.projector.fy);
  const double spot = m.pattern.spot_diameter_px * scale, pitch = m.pattern.pitch_px * scale;
  if (spot >= kMinSpotPx && pitch >= kMinPitchPx) return "";
  return fmt::format(
      "the camera images the spots {:.2g} px across at a pitch of {:.2g} px; the decoder needs "
      "at least {:g} px and {:g} px (raise pattern.pitch_px and spot_diameter_px, or the "
      "camera's resolution)",
      spot, pitch, kMinSpotPx, kMinPitchPx);
}

double LitShare(const ModuleDescription& m, double z_mm) {
  const CameraModel camera(m.camera), projector(m.projector);
  constexpr int kSteps = 24;
  int seen = 0, lit = 0;
  for (int i = 0; i < kSteps; ++i) {
    for (int j = 0; j < kSteps; ++j) {
      const Eigen::Vector2d pixel((i + 0.5) * m.camera.width / kSteps - 0.5,
                                  (j + 0.5) * m.camera.height / kSteps - 0.5);
      const auto xy = camera.Unproject(pixel);
      if (!xy) continue;
      ++seen;
      const Eigen::Vector3d wall(xy->x() * z_mm, xy->y() * z_mm, z_mm);
      const auto uv = projector.Project(m.projector_from_camera * wall);
      lit += uv && uv->x() >= -0.5 && uv->y() >= -0.5 && uv->x() <= m.projector.width - 0.5 &&
             uv->y() <= m.projector.height - 0.5;
    }
  }
  return seen > 0 ? static_cast<double>(lit) / seen : 0.0;
}

std::string FieldOverlapProblem(const ModuleDescription& m) {
  constexpr double kMinShare = 1.0 / 3.0;
  double best = 0.0, at = kWorkingDistanceMinMm;
  for (double z = kWorkingDistanceMinMm; z <= kWorkingDistanceMaxMm + 1e-9; z += 25.0) {
    if (const double share = LitShare(m, z); share > best) best = share, at = z;
  }
  if (best >= kMinShare) return "";
  return fmt::format(
      "the projector lights at most {:.0f} % of the camera's view on a wall {:g}-{:g} mm away "
      "({:g} mm): the fields do not meet (is projector_from_camera's translation on the right "
      "side, its rotation turned toward the camera's view?)",
      100.0 * best, kWorkingDistanceMinMm, kWorkingDistanceMaxMm, at);
}

std::string WindowFitProblem(const ModuleDescription& m, int window) {
  const double window_px = window * m.pattern.pitch_px;
  if (window_px <= std::min(m.projector.width, m.projector.height)) return "";
  return fmt::format(
      "a {0}x{0} pattern window at pitch {1:g} px spans {2:g} px, more than the {3}x{4} "
      "projector: no window can be decoded (lower pattern.pitch_px)",
      window, m.pattern.pitch_px, window_px, m.projector.width, m.projector.height);
}

std::optional<UsabilityProblem> FindUsabilityProblem(const ModuleDescription& module, int rows,
                                                     int cols, int window) {
  using Cause = UsabilityProblem::Cause;
  if (std::string text = DepthPrecisionProblem(module); !text.empty())
    return UsabilityProblem{Cause::kDepthPrecision, std::move(text)};
  if (std::string text = SpotSizeProblem(module); !text.empty())
    return UsabilityProblem{Cause::kSpotSize, std::move(text)};
  if (std::string text = FieldOverlapProblem(module); !text.empty())
    return UsabilityProblem{Cause::kFieldOverlap, std::move(text)};
  if (std::string text = WindowFitProblem(module, window); !text.empty())
    return UsabilityProblem{Cause::kWindowFit, std::move(text)};
  const DisparityRange range =
      ComputeDisparityRange(module, kWorkingDistanceMinMm, kWorkingDistanceMaxMm);
  if (std::string text = PatternSpanProblem(range, rows, cols); !text.empty())
    return UsabilityProblem{Cause::kPatternSpan, std::move(text)};
  return std::nullopt;
}

}  // namespace sewer3d
