// `sewer3d evaluate plane|cylinder`: fits the surface to a cloud and prints the accuracy
// figures of the paper's Tables 1 and 2, plus errors against the truth when it is known.

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sewer3d/cli/evaluate_commands.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/ply_io.hpp"
#include "sewer3d/model/cloud_facts.hpp"
#include "sewer3d/model/fit.hpp"
#include "sewer3d/simeval/residual_image.hpp"
#include "sewer3d/simio/scene_io.hpp"

namespace sewer3d::cli {
namespace {

using Points = std::vector<Eigen::Vector3d>;

// A cloud that is probably not in millimetres is warned of, after the fit: a cloud no surface
// fits gets its one error line.
void WarnOfUnits(const std::string& cloud, const CameraCloudFacts& facts) {
  const std::string problem = CloudUnitsProblem(facts);
  if (problem.empty()) return;
  std::fflush(stdout);
  fmt::print(stderr, "sewer3d: warning: {}: {}\n", cloud, problem);
}

// Each point's signed distance from the fitted surface (positive away from the camera).
using Residuals = std::function<double(const Eigen::Vector3d&)>;

Residuals PrintPlane(const std::string& cloud, const Points& points) {
  const auto fit = FitPlane(points);
  if (!fit) throw FileError(cloud, "points do not span a plane");
  // A plane nearly parallel to the optical axis meets it far away or never.
  const std::string crossing =
      std::abs(fit->normal.z()) > 1e-3
          ? fmt::format("plane at {:.3f} mm on the optical axis", -fit->offset / fit->normal.z())
          : "plane parallel to the optical axis";
  fmt::print("plane      median distance to the camera {:.3f} mm, {}\n",
             DescribeCameraCloud(points).median_distance_mm, crossing);
  fmt::print("fit        RMS {:.4f} mm, max {:.4f} mm\n", fit->rms_mm, fit->max_mm);
  return [plane = *fit](const Eigen::Vector3d& p) { return SignedDistance(plane, p); };
}

Residuals PrintCylinder(const std::string& cloud, const Points& points,
                        const std::optional<Scene>& truth) {
  const auto fit = FitCylinderAnyAxis(points);
  if (!fit || !fit->converged) {
    throw FileError(cloud,
                    "no cylinder fits the points (identical or collinear points, or the fit did "
                    "not converge)");
  }
  if (fit->flat) {
    throw FileError(cloud, fmt::format("the points lie on a plane (plane RMS {:.4f} mm, cylinder "
                                       "RMS {:.4f} mm): no curvature to measure a diameter "
                                       "from; use evaluate plane",
                                       fit->plane_rms_mm, fit->rms_mm));
  }
  const Eigen::Vector3d& a = fit->axis_direction;
  const Eigen::Vector3d& c = fit->axis_point;
  fmt::print(
      "cylinder   diameter {:.3f} mm, axis ({:.4f}, {:.4f}, {:.4f}) through ({:.2f}, {:.2f}, "
      "{:.2f}) mm\n",
      2 * fit->radius_mm, a.x(), a.y(), a.z(), c.x(), c.y(), c.z());
  fmt::print("fit        RMS {:.4f} mm, max {:.4f} mm\n", fit->rms_mm, fit->max_mm);
  Residuals residuals = [cylinder = *fit](const Eigen::Vector3d& p) {
    return SignedDistance(cylinder, p);
  };
  if (!truth) return residuals;
  const double error = 2 * fit->radius_mm - truth->diameter_mm;
  // A cylinder through a wall's joint step and relief is not the pipe's: said on the line.
  const std::size_t n = truth->features.size();
  fmt::print("truth      diameter {:.3f} mm: error {:+.3f} mm ({:+.3f} %{})\n", truth->diameter_mm,
             error, 100 * error / truth->diameter_mm,
             n ? fmt::format(", the fit holding the wall's {} features", n) : "");
  return residuals;
}

void PrintTruthDistances(const Scene& scene, const Points& all) {
  double sum2 = 0.0, worst = 0.0;
  int beyond_1mm = 0;
  for (const auto& p : all) {
    const double d = DistanceToSurfaceMm(scene, p);
    sum2 += d * d;
    worst = std::max(worst, d);
    beyond_1mm += d > 1.0;
  }
  fmt::print(
      "truth      all {} points to the true surface: RMS {:.4f} mm, max {:.4f} mm, {} farther "
      "than 1 mm\n",
      all.size(), std::sqrt(sum2 / all.size()), worst, beyond_1mm);
}

}  // namespace

int RunEvaluateSurface(const std::string& surface, const std::string& cloud,
                       const std::string& truth_file, double inner_fraction,
                       const std::string& out) {
  // Every input read before any work: a bad --truth fails at once.
  std::optional<Scene> truth;
  if (!truth_file.empty()) truth = ReadScene(truth_file);
  if (truth && surface == "cylinder" && truth->type == Scene::Type::kPlane) {
    throw FileError(truth_file,
                    "the true scene is a plane; evaluate cylinder needs a cylinder or pipe-wall "
                    "scene");
  }
  if (truth && surface == "plane" && truth->type != Scene::Type::kPlane) {
    throw FileError(truth_file,
                    "the true scene is a cylinder or pipe wall; evaluate plane needs a plane "
                    "scene (evaluate cylinder fits this one)");
  }
  std::string frame;
  const Points all = ReadPlyPoints(cloud, &frame);
  if (!frame.empty() && frame != kCameraFrame) {
    throw FileError(cloud, "its points are in the " + frame +
                               " (its header says so); evaluate plane|cylinder judges a "
                               "camera-frame cloud of reconstruct or rgbd (the model's own fit "
                               "is in WS/model/report.json)");
  }
  const CameraCloudFacts facts = DescribeCameraCloud(all);
  if (!all.empty() && facts.behind == all.size()) {
    throw FileError(cloud, fmt::format("all {} points lie behind the camera (z <= 0): evaluate "
                                       "reads a cloud in the camera frame (z along the view)",
                                       all.size()));
  }
  if (facts.behind > 0) {
    std::fflush(stdout);
    fmt::print(stderr,
               "sewer3d: warning: {}: {} of the {} points lie behind the camera (z <= 0) "
               "and are left out\n",
               cloud, facts.behind, all.size());
  }
  const Points points = InnerPoints(all, inner_fraction);
  if (points.size() < 10 && all.size() >= 10) {  // the option leaves too few, not the file
    throw InvalidValue("--inner-fraction",
                       fmt::format("{} keeps {} of the {} points of {}; at least 10 are needed",
                                   inner_fraction, points.size(), all.size(), cloud));
  }
  if (points.size() < 10)
    throw FileError(cloud, fmt::format("only {} points: at least 10 are needed", all.size()));
  fmt::print("{}: {} points, {} in the inner {:.0f} %\n", cloud, all.size(), points.size(),
             100 * inner_fraction);
  const Residuals fitted =
      surface == "plane" ? PrintPlane(cloud, points) : PrintCylinder(cloud, points, truth);
  WarnOfUnits(cloud, facts);
  if (truth) PrintTruthDistances(*truth, all);
  if (!out.empty()) {
    std::vector<double> residuals(all.size());
    std::transform(all.begin(), all.end(), residuals.begin(), fitted);
    const std::string title = fmt::format(
        "signed distance from the {} fitted to the inner {:.0f} %", surface, 100 * inner_fraction);
    std::filesystem::create_directories(out);
    for (const NamedPicture& p : ResidualPictures(all, residuals, title, truth ? &*truth : nullptr))
      WriteImage(std::filesystem::path(out) / p.file, p.image);
  }
  return 0;
}

}  // namespace sewer3d::cli
