#include "sewer3d/posegraph/axis_curve.hpp"

#include <algorithm>
#include <cmath>

#include "sewer3d/posegraph/axis_curve_cost.hpp"

namespace sewer3d {
int AxisCurve::Segment(double station_mm) const {
  const int last = static_cast<int>(points.size()) - 2;
  const double k = std::floor((station_mm - start_station_mm) / spacing_mm);
  return static_cast<int>(std::clamp(k, 0.0, static_cast<double>(std::max(last, 0))));
}

Eigen::Vector3d AxisCurve::At(double station_mm) const {
  const int k = Segment(station_mm);
  const double f = Fraction(k, station_mm);
  return points[k] + f * (points[k + 1] - points[k]);
}

Eigen::Vector4d AxisResidual(const AxisObservation& observation, const Rigid3d& world_from_node,
                             const AxisCurve& curve) {
  const int k = curve.Segment(observation.station_mm);
  const AxisCost cost(observation, curve.Fraction(k, observation.station_mm));
  const Eigen::Quaterniond q = world_from_node.rotation;
  Eigen::Vector4d r;
  cost(world_from_node.translation.data(), q.coeffs().data(), curve.points[k].data(),
       curve.points[k + 1].data(), r.data());
  return r;
}

Eigen::Vector4d CurvatureResidual(const AxisCurve& curve, int k) {
  const CurvatureCost cost(curve.curvature_sigma_mm[k], curve.along_sigma_mm);
  const std::vector<Eigen::Vector3d>& c = curve.points;
  Eigen::Vector4d r;
  cost(c[k].data(), c[k + 1].data(), c[k + 2].data(), r.data());
  return r;
}

double ProjectStation(const AxisObservation& observation, const Rigid3d& world_from_node,
                      const AxisCurve& curve) {
  const int k = curve.Segment(observation.station_mm);
  const Eigen::Vector3d segment = curve.points[k + 1] - curve.points[k];
  const Eigen::Vector3d d =
      world_from_node * observation.in_node - curve.At(observation.station_mm);
  // Along the segment in mm, into stations (a segment spans `spacing_mm` of them).
  return observation.station_mm + segment.dot(d) / segment.squaredNorm() * curve.spacing_mm;
}

}  // namespace sewer3d
