#include "sewer3d/texture/module_gains.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

double Median(std::vector<double>& v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

void SeamOptions::Check() const {
  SEWER3D_VALIDATE(stride_px >= 1, "stride_px", "must be at least 1, got " << stride_px);
  ValidatePositive("max_depth_step_mm", max_depth_step_mm);
  SEWER3D_VALIDATE(min_points >= 1, "min_points", "must be at least 1, got " << min_points);
  ValidatePositive("min_linear", min_linear);
}

std::optional<SeamRatio> MeasureSeamRatio(const cv::Mat3f& colour_a, const cv::Mat1f& depth_a,
                                          const CameraModel& camera_a, const cv::Mat3f& colour_b,
                                          const cv::Mat1f& depth_b, const CameraModel& camera_b,
                                          const Rigid3d& b_from_a, const SeamOptions& options) {
  options.Check();
  SEWER3D_VALIDATE(colour_a.size() == depth_a.size() && colour_b.size() == depth_b.size(), "depth",
                   "must have its colour image's size");
  std::array<std::vector<double>, 3> logs;
  for (int v = 0; v < depth_a.rows; v += options.stride_px) {
    for (int u = 0; u < depth_a.cols; u += options.stride_px) {
      const float z = depth_a(v, u);
      const auto xy = camera_a.Unproject({double(u), double(v)});
      if (!std::isfinite(z) || !xy) continue;
      const Eigen::Vector3d p_b = b_from_a * (double(z) * Eigen::Vector3d(xy->x(), xy->y(), 1.0));
      const auto px = camera_b.Project(p_b);
      if (!px) continue;
      const int ub = static_cast<int>(std::lround(px->x()));
      const int vb = static_cast<int>(std::lround(px->y()));
      if (ub < 0 || vb < 0 || ub >= depth_b.cols || vb >= depth_b.rows) continue;
      if (!(std::abs(depth_b(vb, ub) - p_b.z()) < options.max_depth_step_mm)) continue;
      const cv::Vec3f& a = colour_a(v, u);
      const cv::Vec3f& b = colour_b(vb, ub);
      bool bright = true;
      for (int c = 0; c < 3; ++c)
        bright = bright && a[c] > options.min_linear && b[c] > options.min_linear;
      if (!bright) continue;
      for (int c = 0; c < 3; ++c) logs[c].push_back(std::log(double(a[c]) / double(b[c])));
    }
  }
  if (static_cast<int>(logs[0].size()) < options.min_points) return std::nullopt;
  SeamRatio ratio;
  ratio.points = static_cast<int>(logs[0].size());
  for (int c = 0; c < 3; ++c) ratio.log_ratio_bgr[c] = Median(logs[c]);
  return ratio;
}

ModuleGains SolveModuleGains(int modules, const std::vector<SeamMeasurement>& seams) {
  SEWER3D_VALIDATE(modules >= 1, "modules", "must be at least 1, got " << modules);
  std::vector<bool> reached(modules, false);
  for (const SeamMeasurement& s : seams) {
    SEWER3D_VALIDATE(s.a >= 0 && s.a < modules && s.b >= 0 && s.b < modules && s.a != s.b, "seams",
                     "module index out of range or a seam of a module with itself");
    reached[s.a] = reached[s.b] = true;
  }
  ModuleGains out;
  out.gains_bgr.assign(modules, cv::Vec3d(1, 1, 1));
  out.seams = static_cast<int>(seams.size());
  if (seams.empty()) return out;
  // Normal equations of the weighted differences plus the gauge Σ log g = 0 (reached modules).
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(modules, modules);
  for (int m = 0; m < modules; ++m) {
    if (!reached[m]) normal(m, m) = 1.0;  // kept at log g = 0
  }
  for (const SeamMeasurement& s : seams) {
    const double w = s.ratio.points;
    normal(s.a, s.a) += w;
    normal(s.b, s.b) += w;
    normal(s.a, s.b) -= w;
    normal(s.b, s.a) -= w;
  }
  double total = 0;
  for (const SeamMeasurement& s : seams) total += s.ratio.points;
  Eigen::VectorXd gauge = Eigen::VectorXd::Zero(modules);
  for (int m = 0; m < modules; ++m) gauge(m) = reached[m] ? 1.0 : 0.0;
  normal += total * gauge * gauge.transpose();
  const Eigen::LDLT<Eigen::MatrixXd> solver(normal);
  double sum_squares = 0;
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(modules);
    for (const SeamMeasurement& s : seams) {
      rhs(s.a) += s.ratio.points * s.ratio.log_ratio_bgr[c];
      rhs(s.b) -= s.ratio.points * s.ratio.log_ratio_bgr[c];
    }
    const Eigen::VectorXd log_gain = solver.solve(rhs);
    for (int m = 0; m < modules; ++m) out.gains_bgr[m][c] = std::exp(log_gain(m));
    for (const SeamMeasurement& s : seams) {
      const double r = log_gain(s.a) - log_gain(s.b) - s.ratio.log_ratio_bgr[c];
      sum_squares += r * r;
    }
  }
  out.rms_log_residual = std::sqrt(sum_squares / (3.0 * static_cast<double>(seams.size())));
  return out;
}

}  // namespace sewer3d
