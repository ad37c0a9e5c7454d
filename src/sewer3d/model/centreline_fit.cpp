#include "sewer3d/model/centreline_fit.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "sewer3d/core/check.hpp"
#include "sewer3d/model/axis_curve.hpp"
#include "sewer3d/model/unroll.hpp"

namespace sewer3d {
namespace {

double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

// Fits one circle per slice of the points unrolled about `line`; each point's 2D coordinates
// are its offset from the axis in the normal plane at its own station (crown, right), so a
// slice's circle centre is the correction to the axis at the slice's station.
std::vector<SliceReport> FitSlices(const Centreline& line, const std::vector<Eigen::Vector3d>& pts,
                                   std::vector<double>& stations,
                                   const CentrelineFitOptions& options) {
  std::map<long, std::vector<Eigen::Vector2d>> slices;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const CylPoint c = Unroll(line, pts[i], stations[i]);
    stations[i] = c.station_mm;
    const auto k = static_cast<long>(std::floor(c.station_mm / options.slice_spacing_mm));
    slices[k].emplace_back(c.radius_mm * std::cos(c.clock_rad),
                           c.radius_mm * std::sin(c.clock_rad));
  }
  std::vector<SliceReport> reports;
  for (const auto& [k, q] : slices) {
    SliceReport r;
    r.station_mm = (static_cast<double>(k) + 0.5) * options.slice_spacing_mm;
    r.points = static_cast<int>(q.size());
    if (r.points < options.min_slice_points) {
      reports.push_back(r);
      continue;
    }
    const CircleFit fit = FitCircleRobust(q, options.circle);
    const AxisFrame f = line.FrameAt(r.station_mm);
    r.centre = f.origin + fit.centre.x() * f.crown + fit.centre.y() * f.right;
    r.radius_mm = fit.radius_mm, r.ovality_mm = fit.ovality_mm, r.rms_mm = fit.rms_mm;
    r.inlier_fraction = fit.inlier_fraction, r.coverage_deg = fit.coverage_deg;
    r.used = fit.converged && r.coverage_deg >= options.min_slice_coverage_deg &&
             r.inlier_fraction >= options.min_inlier_fraction;
    reports.push_back(r);
  }
  return reports;
}

std::vector<AxisSample> UsedSamples(const std::vector<SliceReport>& slices) {
  std::vector<AxisSample> samples;
  for (const auto& s : slices) {
    if (s.used) samples.push_back({s.station_mm, s.centre});
  }
  return samples;
}

// The curve (sampled at stations s0 + j·step) at station s, linearly interpolated.
Eigen::Vector3d CurveAt(const std::vector<Eigen::Vector3d>& curve, double s0, double step,
                        double s) {
  const double u = std::clamp((s - s0) / step, 0.0, static_cast<double>(curve.size() - 1));
  const auto j = std::min(static_cast<std::size_t>(u), curve.size() - 2);
  const double w = u - static_cast<double>(j);
  return (1.0 - w) * curve[j] + w * curve[j + 1];
}

}  // namespace

void CentrelineFitOptions::Check() const {
  ValidatePositive("nominal_diameter_mm", nominal_diameter_mm);
  SEWER3D_VALIDATE(initial_axis.norm() > 0.0, "initial_axis", "must not be zero");
  ValidatePositive("slice_spacing_mm", slice_spacing_mm);
  ValidatePositive("step_mm", step_mm);
  ValidatePositive("smoothing_half_width_mm", smoothing_half_width_mm);
  SEWER3D_VALIDATE(min_slice_points >= 8, "min_slice_points",
                   "must be >= 8, got " << min_slice_points);
  ValidateNotNegative("min_slice_coverage_deg", min_slice_coverage_deg);
  ValidateNotNegative("min_inlier_fraction", min_inlier_fraction);
  ValidatePositive("slice_outlier_mm", slice_outlier_mm);
  ValidatePositive("slice_outlier_scales", slice_outlier_scales);
  SEWER3D_VALIDATE(max_iterations >= 1, "max_iterations", "must be >= 1, got " << max_iterations);
  ValidatePositive("convergence_mm", convergence_mm);
  ValidatePositive("bend_min_sagitta_mm", bend_min_sagitta_mm);
  CheckWithin("circle.", [&] { circle.Check(); });
}

CentrelineFit FitCentreline(const std::vector<Eigen::Vector3d>& points_model,
                            const CentrelineFitOptions& options) {
  options.Check();
  CentrelineFit result;
  if (points_model.empty()) return result;
  // The initial axis as a two-point curve covering the points' extent along it.
  const Eigen::Vector3d a = options.initial_axis.normalized();
  double t_lo = 1e300, t_hi = -1e300;
  for (const auto& p : points_model)
    t_lo = std::min(t_lo, p.dot(a)), t_hi = std::max(t_hi, p.dot(a));
  auto line = ResampleAxis({(t_lo - 1.0) * a, (t_hi + 1.0) * a}, options.step_mm);
  if (!line) return result;
  std::vector<double> stations(points_model.size(), 0.0);
  const std::size_t min_samples = options.straight ? 2 : 3;
  CentrelineFitReport& report = result.report;
  for (report.iterations = 1; report.iterations <= options.max_iterations; ++report.iterations) {
    report.slices = FitSlices(*line, points_model, stations, options);
    std::vector<double> at;
    const double s0 =
        std::floor(report.slices.front().station_mm / options.step_mm - 3) * options.step_mm;
    for (double s = s0; s < report.slices.back().station_mm + 3 * options.step_mm;
         s += options.step_mm)
      at.push_back(s);
    std::vector<AxisSample> samples = UsedSamples(report.slices);
    if (samples.size() < min_samples) return result;
    auto curve = SmoothAxis(samples, at, options.smoothing_half_width_mm, options.straight);
    // Slices whose centre is off the smooth axis (a displaced joint, a poor fit) are dropped.
    std::vector<double> off;
    for (const auto& s : samples)
      off.push_back((s.centre - CurveAt(curve, s0, options.step_mm, s.station_mm)).norm());
    const double limit =
        std::max(options.slice_outlier_mm, options.slice_outlier_scales * 1.4826 * Median(off));
    for (auto& s : report.slices) {
      if (s.used && (s.centre - CurveAt(curve, s0, options.step_mm, s.station_mm)).norm() > limit)
        s.used = false;
    }
    samples = UsedSamples(report.slices);
    if (samples.size() < min_samples) return result;
    curve = SmoothAxis(samples, at, options.smoothing_half_width_mm, options.straight);
    report.last_move_mm = 0.0;
    for (std::size_t j = 0; j < at.size(); ++j) {
      if (at[j] < samples.front().station_mm || at[j] > samples.back().station_mm) continue;
      report.last_move_mm =
          std::max(report.last_move_mm, (curve[j] - line->FrameAt(at[j]).origin).norm());
    }
    line = ResampleAxis(curve, options.step_mm);
    if (!line) return result;
    if (report.last_move_mm < options.convergence_mm) break;
  }
  report.iterations = std::min(report.iterations, options.max_iterations);
  // Report on the final slices.
  std::vector<double> radii;
  double sum2 = 0.0, inliers = 0.0, axis2 = 0.0;
  for (auto& s : report.slices) {
    const double off_axis_mm = Unroll(*line, s.centre, s.station_mm).radius_mm;
    s.station_mm += options.start_station_mm;
    if (!s.used) {
      ++report.slices_rejected;
      continue;
    }
    ++report.slices_used;
    radii.push_back(s.radius_mm);
    const double n = s.inlier_fraction * s.points;
    sum2 += n * s.rms_mm * s.rms_mm, inliers += n;
    axis2 += off_axis_mm * off_axis_mm;
  }
  report.radius_mm = Median(radii);
  report.rms_mm = inliers > 0 ? std::sqrt(sum2 / inliers) : 0.0;
  report.axis_rms_mm = std::sqrt(axis2 / std::max(1, report.slices_used));
  report.bend_radius_mm = FitBendRadius(*line, options.bend_min_sagitta_mm);
  result.centreline = *line;
  result.centreline.station0_mm += options.start_station_mm;
  result.centreline.radius_mm = options.nominal_diameter_mm / 2.0;
  result.converged = true;
  return result;
}

}  // namespace sewer3d
