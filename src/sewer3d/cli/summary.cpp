#include "sewer3d/cli/summary.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/camera/field_of_view.hpp"
#include "sewer3d/camera/module_checks.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/pattern/constraints.hpp"

namespace sewer3d::cli {

std::string PrintModuleSummary(const ModuleDescription& m, const BinaryArray& pattern) {
  const CameraModel camera(m.camera), projector(m.projector);
  fmt::print(
      "camera     {}x{} px, f {:.1f}/{:.1f} px, principal point ({:.1f}, {:.1f}), k [{:g}, {:g}, "
      "{:g}]\n",
      m.camera.width, m.camera.height, m.camera.fx, m.camera.fy, m.camera.cx, m.camera.cy,
      m.camera.k[0], m.camera.k[1], m.camera.k[2]);
  const double fov_x = FieldOfViewDeg(camera, true), fov_y = FieldOfViewDeg(camera, false);
  fmt::print("           field of view {:.1f} x {:.1f} deg{}\n", fov_x, fov_y,
             camera.WholeImageInvertible() ? "" : " (distortion folds over inside the image!)");
  fmt::print("projector  {}x{} px, f {:.1f}/{:.1f} px, principal point ({:.1f}, {:.1f})\n",
             m.projector.width, m.projector.height, m.projector.fx, m.projector.fy, m.projector.cx,
             m.projector.cy);
  const Eigen::Vector3d projector_centre = m.projector_from_camera.Inverse().translation;
  fmt::print("baseline   {:.2f} mm, projector centre in camera frame ({:.2f}, {:.2f}, {:.2f}) mm\n",
             projector_centre.norm(), projector_centre.x(), projector_centre.y(),
             projector_centre.z());

  const DisparityRange range =
      ComputeDisparityRange(m, kWorkingDistanceMinMm, kWorkingDistanceMaxMm);
  fmt::print(
      "disparity  walls {:.0f}-{:.0f} mm from the camera: {:.0f} px along projector u "
      "({:.1f} columns of {:g} px), {:.1f} px along v ({:.2f} rows)\n",
      kWorkingDistanceMinMm, kWorkingDistanceMaxMm, range.max_du_px, range.max_cols,
      m.pattern.pitch_px, range.max_dv_px, range.max_rows);

  fmt::print("depth      ±{:.2f} mm at {:g} mm for {:g} px of disparity error\n",
             DepthErrorMm(m, kWorkingDistanceMaxMm), kWorkingDistanceMaxMm, kDisparityErrorPx);
  if (std::string problem = DepthPrecisionProblem(m); !problem.empty()) return problem;
  if (std::string problem = SpotSizeProblem(m); !problem.empty()) return problem;
  if (std::string problem = FieldOverlapProblem(m); !problem.empty()) return problem;

  PatternConstraints constraints;
  PatternReport report = VerifyPattern(pattern, constraints);
  std::string kind = "torus";
  if (!report.valid) {
    constraints.torus = false;
    const PatternReport plain = VerifyPattern(pattern, constraints);
    if (plain.valid) {
      report = plain;
      kind = "plain (windows inside the tile only)";
    }
  }
  fmt::print("pattern    {} ({}), pitch {:g} px, spot {:g} px: {}\n", m.pattern.matrix_path, kind,
             m.pattern.pitch_px, m.pattern.spot_diameter_px, Describe(report));
  const bool spans = pattern.cols > range.max_cols;
  const int needed = static_cast<int>(std::ceil(range.max_cols));
  fmt::print("           {} columns {} the {} the disparity range needs\n", pattern.cols,
             spans ? "cover" : "do NOT cover", needed);
  // As PatternSpanProblem judges it.
  const bool rows_cover = range.max_dv_px <= range.max_du_px || pattern.rows > range.max_rows;
  if (!rows_cover) {
    fmt::print("           {} rows do NOT cover the {:.0f} the disparity along v needs\n",
               pattern.rows, std::ceil(range.max_rows));
  }
  if (std::string problem = WindowFitProblem(m, constraints.window); !problem.empty())
    return problem;
  if (!report.valid) return "the pattern matrix violates its constraints: " + Describe(report);
  return PatternSpanProblem(range, pattern.rows, pattern.cols);
}

}  // namespace sewer3d::cli
