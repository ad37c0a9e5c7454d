// `sewer3d evaluate plane|cylinder`: fits the surface to a cloud and prints the accuracy
// figures of the paper's Tables 1 and 2, plus errors against the truth when it is known.
// `sewer3d evaluate rgbd`: the RGB-D stage's colour against a simulated run's truth
// (cmd_evaluate_rgbd.cpp); `registration` and `model` likewise (cmd_evaluate_registration.cpp,
// cmd_evaluate_model.cpp).

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/evaluate_commands.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/ply_io.hpp"
#include "sewer3d/model/fit.hpp"
#include "sewer3d/pipeline/workspace.hpp"
#include "sewer3d/simeval/rgbd_evaluation.hpp"
#include "sewer3d/simio/scene_io.hpp"

namespace sewer3d::cli {

Command AddEvaluateCommand(CLI::App& app) {
  struct Args {
    std::string surface, cloud, truth, run, workspace, out;
    int smoothing_px = RgbdEvaluationOptions{}.colour_smoothing_px;
    int stride = 0;
    double inner_fraction = 0.5;
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub =
      app.add_subcommand("evaluate",
                         "Accuracy against the truth: a plane or cylinder fitted to a cloud, or a "
                         "processing stage on a simulated run (rgbd)");
  sub->add_option("what", args->surface, "plane, cylinder, rgbd, registration, model or inspection")
      ->required()
      ->check(CLI::IsMember({"plane", "cylinder", "rgbd", "registration", "model", "inspection"}));
  sub->add_option("--cloud", args->cloud, "plane, cylinder: point cloud (PLY, camera frame, mm)");
  sub->add_option("--run", args->run,
                  "rgbd, registration, model, inspection: the simulated capture run (with truth/)");
  sub->add_option("--smoothing-px", args->smoothing_px,
                  "rgbd: colours compared after a box mean of this side (1: per pixel)")
      ->capture_default_str()
      ->check(CLI::Range(1, 101));
  sub->add_option("--workspace", args->workspace,
                  "rgbd, registration, model, inspection: the processing workspace WS");
  sub->add_option(
      "--out", args->out,
      "rgbd, registration, model, inspection: folder for evaluation.json and pictures (default "
      "WS/evaluation/<what>)");
  sub->add_option("--stride", args->stride,
                  "model: every n-th map row and column (0: automatic, about 3 M cells)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  sub->add_option("--inner-fraction", args->inner_fraction,
                  "Central fraction of the view used for the fit")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 1.0));
  sub->add_option("--truth", args->truth,
                  "scene.json of the simulated capture: errors against the true surface");
  return {sub, [args, sub] {
            const bool of_workspace = args->surface != "plane" && args->surface != "cylinder";
            // Options of the other kind of evaluation are refused, not ignored.
            const std::vector<std::string> others =
                of_workspace ? std::vector<std::string>{"--cloud", "--truth", "--inner-fraction"}
                             : std::vector<std::string>{"--run", "--workspace", "--out", "--stride",
                                                        "--smoothing-px"};
            for (const std::string& name : others) {
              if (sub->get_option(name)->count() > 0) {
                throw InvalidValue(name, "does not apply to evaluate " + args->surface);
              }
            }
            if (of_workspace && !args->run.empty() && !args->workspace.empty())
              CheckWorkspaceOfRun(args->workspace, args->run);
            if (args->surface == "rgbd") {
              if (args->run.empty() || args->workspace.empty())
                throw InvalidValue("--run, --workspace", "evaluate rgbd needs both");
              return RunEvaluateRgbd(args->run, args->workspace, args->out, args->smoothing_px);
            }
            if (args->surface == "registration") {
              if (args->run.empty() || args->workspace.empty())
                throw InvalidValue("--run, --workspace", "evaluate registration needs both");
              return RunEvaluateRegistration(args->run, args->workspace, args->out);
            }
            if (args->surface == "model") {
              if (args->run.empty() || args->workspace.empty())
                throw InvalidValue("--run, --workspace", "evaluate model needs both");
              return RunEvaluateModel(args->run, args->workspace, args->out, args->stride);
            }
            if (args->surface == "inspection") {
              if (args->run.empty() || args->workspace.empty())
                throw InvalidValue("--run, --workspace", "evaluate inspection needs both");
              return RunEvaluateInspection(args->run, args->workspace, args->out);
            }
            if (args->cloud.empty()) throw CLI::RequiredError("--cloud");
            // Every input read before any work: a bad --truth fails at once.
            std::optional<Scene> truth;
            if (!args->truth.empty()) truth = ReadScene(args->truth);
            if (truth && args->surface == "cylinder" && truth->type == Scene::Type::kPlane) {
              throw FileError(args->truth,
                              "the true scene is a plane; evaluate cylinder needs a cylinder or "
                              "pipe-wall scene");
            }
            const auto all = ReadPlyPoints(args->cloud);
            const auto points = InnerPoints(all, args->inner_fraction);
            if (points.size() < 10)
              throw FileError(args->cloud,
                              fmt::format("only {} points in the inner part", points.size()));
            std::vector<double> depths;
            for (const auto& p : points) depths.push_back(p.norm());
            std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
            fmt::print("{}: {} points, {} in the inner {:.0f} %\n", args->cloud, all.size(),
                       points.size(), 100 * args->inner_fraction);
            if (args->surface == "plane") {
              const auto fit = FitPlane(points);
              if (!fit) throw FileError(args->cloud, "points do not span a plane");
              fmt::print(
                  "plane      median distance to the camera {:.3f} mm, plane at {:.3f} mm on the "
                  "optical axis\n",
                  depths[depths.size() / 2], -fit->offset / fit->normal.z());
              fmt::print("fit        RMS {:.4f} mm, max {:.4f} mm\n", fit->rms_mm, fit->max_mm);
            } else {
              const auto fit = FitCylinder(points, Eigen::Vector3d::UnitY());
              if (!fit || !fit->converged)
                throw FileError(args->cloud,
                                "no cylinder fits the points (identical or collinear points, "
                                "or the fit did not converge)");
              // A flat cloud "fits" a cylinder of any large radius: a plane that explains the
              // points at least as well means there is no curvature to measure.
              if (const auto plane = FitPlane(points); plane && plane->rms_mm <= fit->rms_mm) {
                throw FileError(args->cloud,
                                fmt::format("the points lie on a plane (plane RMS {:.4f} mm, "
                                            "cylinder RMS {:.4f} mm): no curvature to measure a "
                                            "diameter from; use evaluate plane",
                                            plane->rms_mm, fit->rms_mm));
              }
              fmt::print(
                  "cylinder   diameter {:.3f} mm, axis ({:.4f}, {:.4f}, {:.4f}) through ({:.2f}, "
                  "{:.2f}, {:.2f}) mm\n",
                  2 * fit->radius_mm, fit->axis_direction.x(), fit->axis_direction.y(),
                  fit->axis_direction.z(), fit->axis_point.x(), fit->axis_point.y(),
                  fit->axis_point.z());
              fmt::print("fit        RMS {:.4f} mm, max {:.4f} mm\n", fit->rms_mm, fit->max_mm);
              if (truth) {
                const Scene& scene = *truth;
                fmt::print("truth      diameter {:.3f} mm: error {:+.3f} mm ({:+.3f} %)\n",
                           scene.diameter_mm, 2 * fit->radius_mm - scene.diameter_mm,
                           100 * (2 * fit->radius_mm - scene.diameter_mm) / scene.diameter_mm);
              }
            }
            if (truth) {
              const Scene& scene = *truth;
              double sum2 = 0.0, worst = 0.0;
              int beyond_1mm = 0;
              for (const auto& p : all) {
                const double d = DistanceToSurfaceMm(scene, p);
                sum2 += d * d;
                worst = std::max(worst, d);
                beyond_1mm += d > 1.0;
              }
              fmt::print(
                  "truth      all {} points to the true surface: RMS {:.4f} mm, max {:.4f} mm, {} "
                  "farther than 1 mm\n",
                  all.size(), std::sqrt(sum2 / all.size()), worst, beyond_1mm);
            }
            return 0;
          }};
}

}  // namespace sewer3d::cli
