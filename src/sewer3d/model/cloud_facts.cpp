#include "sewer3d/model/cloud_facts.hpp"

#include <fmt/core.h>

#include <algorithm>

namespace sewer3d {

CameraCloudFacts DescribeCameraCloud(const std::vector<Eigen::Vector3d>& points) {
  CameraCloudFacts facts;
  facts.points = points.size();
  if (points.empty()) return facts;
  Eigen::Vector3d lo = points.front(), hi = points.front();
  std::vector<double> distances;
  distances.reserve(points.size());
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    distances.push_back(p.norm());
    facts.behind += p.z() <= 0.0;
  }
  facts.extent_mm = (hi - lo).norm();
  const auto middle = distances.begin() + static_cast<std::ptrdiff_t>(distances.size() / 2);
  std::nth_element(distances.begin(), middle, distances.end());
  facts.median_distance_mm = *middle;
  return facts;
}

std::string CloudUnitsProblem(const CameraCloudFacts& facts) {
  if (facts.points == 0) return {};
  if (facts.extent_mm < 5.0) {
    return fmt::format(
        "the points span only {:.3g} mm: coordinates are read as millimetres (is the cloud in "
        "metres?)",
        facts.extent_mm);
  }
  if (facts.median_distance_mm < 30.0) {
    return fmt::format(
        "the points lie {:.3g} mm from the camera (median), nearer than a module measures (75 "
        "to 225 mm): coordinates are read as millimetres (is the cloud in centimetres?)",
        facts.median_distance_mm);
  }
  if (facts.median_distance_mm > 1e4) {
    return fmt::format(
        "the points lie {:.3g} m from the camera (median), far beyond any module's reach: "
        "coordinates are read as millimetres (is the cloud in micrometres?)",
        facts.median_distance_mm / 1000.0);
  }
  return {};
}

}  // namespace sewer3d
