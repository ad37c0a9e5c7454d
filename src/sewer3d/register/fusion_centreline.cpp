#include "sewer3d/register/fusion_centreline.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

// The line w = a + b·s that best fits the axis points at the initial poses, as [a b].
Eigen::Matrix<double, 3, 2> FitLine(const std::vector<AcquisitionNode>& nodes,
                                    const std::vector<AxisObservation>& observations) {
  Eigen::MatrixXd design(observations.size(), 2);
  Eigen::MatrixXd points(observations.size(), 3);
  for (size_t i = 0; i < observations.size(); ++i) {
    const AxisObservation& o = observations[i];
    design.row(i) << 1.0, o.station_mm;
    points.row(i) = (nodes[o.node].world_from_camera * o.in_node).transpose();
  }
  const Eigen::MatrixXd coefficients = design.colPivHouseholderQr().solve(points);
  return coefficients.transpose();
}

// Radius of the circle through three points (infinity when they are collinear).
double Radius(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double area2 = (b - a).cross(c - a).norm();
  if (area2 <= 0.0) return std::numeric_limits<double>::infinity();
  return (b - a).norm() * (c - b).norm() * (c - a).norm() / (2.0 * area2);
}

// σ₂ of a second difference over control points `spacing` apart that makes a bend of radius
// `radius` cost χ² = 1 per metre: h² / R per point, one point per h of pipe.
double CurvatureSigma(double spacing_mm, double radius_mm) {
  constexpr double kMetre = 1000.0;
  return spacing_mm * spacing_mm / radius_mm * std::sqrt(kMetre / spacing_mm);
}

bool Textured(double station_mm, double spacing_mm, const std::vector<StationSpan>& textured) {
  return std::any_of(textured.begin(), textured.end(), [&](const StationSpan& span) {
    return span.from_mm <= station_mm + spacing_mm && span.to_mm >= station_mm - spacing_mm;
  });
}

}  // namespace

void CentrelineOptions::Check() const {
  ValidatePositive("centreline.spacing_mm", spacing_mm);
  ValidatePositive("centreline.bend_radius_mm", bend_radius_mm);
  ValidatePositive("centreline.featureless_bend_radius_mm", featureless_bend_radius_mm);
  ValidatePositive("centreline.axis_sigma_mm", axis_sigma_mm);
  ValidatePositive("centreline.axis_along_sigma_mm", axis_along_sigma_mm);
  ValidatePositive("centreline.spacing_sigma_mm", spacing_sigma_mm);
}

std::optional<CentrelineSetup> MakeCentreline(const std::vector<AcquisitionNode>& nodes,
                                              const std::vector<StationSpan>& textured,
                                              const CentrelineOptions& options) {
  options.Check();
  if (!options.enabled) return std::nullopt;
  std::map<int, int> per_counter;
  for (const AcquisitionNode& n : nodes) per_counter[n.counter] += n.axis_in_camera ? 1 : 0;
  std::set<int> counters;
  for (const auto& [counter, count] : per_counter)
    if (count > 0) counters.insert(counter);
  if (counters.size() < 2) return std::nullopt;

  CentrelineSetup setup;
  double first = std::numeric_limits<double>::infinity(), last = -first;
  for (int i = 0; i < static_cast<int>(nodes.size()); ++i) {
    const AcquisitionNode& n = nodes[i];
    if (!n.axis_in_camera) continue;
    AxisObservation o;
    o.node = i;
    o.in_node = *n.axis_in_camera;
    o.station_mm = n.distance_mm;
    o.sigma_mm = options.axis_sigma_mm * std::sqrt(per_counter.at(n.counter));
    o.along_sigma_mm = options.axis_along_sigma_mm;
    setup.observations.push_back(o);
    first = std::min(first, n.distance_mm);
    last = std::max(last, n.distance_mm);
  }
  AxisCurve& c = setup.curve;
  c.spacing_mm = options.spacing_mm;
  c.start_station_mm = first - 0.5 * options.spacing_mm;
  const int count = std::max(
      3, static_cast<int>(std::ceil((last - c.start_station_mm) / options.spacing_mm)) + 1);
  c.along_sigma_mm = options.spacing_sigma_mm;
  for (int k = 1; k + 1 < count; ++k) {
    const double station = c.start_station_mm + k * c.spacing_mm;
    const bool seen = Textured(station, c.spacing_mm, textured);
    setup.featureless_points += seen ? 0 : 1;
    c.curvature_sigma_mm.push_back(CurvatureSigma(
        c.spacing_mm, seen ? options.bend_radius_mm : options.featureless_bend_radius_mm));
  }
  const Eigen::Matrix<double, 3, 2> line = FitLine(nodes, setup.observations);
  for (int k = 0; k < count; ++k) {
    const double s = c.start_station_mm + k * c.spacing_mm;
    c.points.push_back(line.col(0) + s * line.col(1));
  }
  return setup;
}

void ReassociateStations(CentrelineSetup& setup, const std::vector<Rigid3d>& poses) {
  const AxisCurve& c = setup.curve;
  const double low = c.start_station_mm - c.spacing_mm;
  const double high = c.start_station_mm + c.spacing_mm * static_cast<double>(c.points.size());
  for (AxisObservation& o : setup.observations)
    o.station_mm = std::clamp(ProjectStation(o, poses[o.node], c), low, high);
}

CentrelineReport ReportCentreline(const CentrelineSetup& setup, const std::vector<Rigid3d>& poses) {
  const AxisCurve& c = setup.curve;
  CentrelineReport r;
  r.observations = static_cast<int>(setup.observations.size());
  r.points = static_cast<int>(c.points.size());
  r.featureless_points = setup.featureless_points;
  r.length_mm = (c.points.back() - c.points.front()).norm();
  for (const AxisObservation& o : setup.observations) {
    // The across part of the residual, in mm (the residual divides it by σ).
    const double across = AxisResidual(o, poses[o.node], c).head<3>().norm() * o.sigma_mm;
    r.across_rms_mm += across * across;
    r.across_max_mm = std::max(r.across_max_mm, across);
  }
  if (r.observations > 0) r.across_rms_mm = std::sqrt(r.across_rms_mm / r.observations);
  // A shorter curve's bend is its points' noise (0.2 mm of sagitta over 0.2 m reads 25 m).
  constexpr double kMinBendLengthMm = 1000.0;
  r.bend_radius_mm = r.length_mm < kMinBendLengthMm
                         ? std::numeric_limits<double>::infinity()
                         : Radius(c.points.front(), c.points[c.points.size() / 2], c.points.back());
  const Eigen::Vector3d chord = (c.points.back() - c.points.front()).normalized();
  for (const Eigen::Vector3d& p : c.points) {
    const Eigen::Vector3d d = p - c.points.front();
    r.max_sagitta_mm = std::max(r.max_sagitta_mm, (d - d.dot(chord) * chord).norm());
  }
  return r;
}

}  // namespace sewer3d
