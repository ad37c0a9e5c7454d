// `sewer3d register RUN --out WS`: the registration stage over a whole capture run
// (docs/registration.md).

#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/process_command.hpp"
#include "sewer3d/cli/progress_bar.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/pipeline/process_chain.hpp"
#include "sewer3d/pipeline/register_stage.hpp"
#include "sewer3d/pipeline/rgbd_inputs.hpp"
#include "sewer3d/pipeline/workspace.hpp"

namespace sewer3d::cli {

Command AddRegisterCommand(CLI::App& app) {
  struct Args {
    std::string run, out;
    int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    bool quiet = false, force = false;
    double inclinometer_sigma_deg = FusionOptions{}.gravity_sigma_deg;
    double featureless_bend_radius_m = CentrelineOptions{}.featureless_bend_radius_mm / 1000.0;
    std::vector<std::string> edges{"feature", "projection",   "texture", "rig",     "odometry",
                                   "scale",   "straightness", "bias",    "gravity", "centreline"};
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "register",
      "Every acquisition of a run into one frame: WS/registration/poses.csv, graph.g2o, "
      "edges.csv, report.json, graph.png (needs WS/rgbd from `sewer3d rgbd`)");
  sub->add_option("RUN", args->run, "Capture run folder (docs/formats.md)")->required();
  sub->add_option("--out", args->out, "Processing workspace folder WS")->required();
  sub->add_option("--threads", args->threads, "Pairs registered at once")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  sub->add_option("--edges", args->edges,
                  "Edge types the graph may use (ablation): feature, projection, texture (the "
                  "projection edges' photometric term), rig, odometry, straightness, bias (the "
                  "bias shared by the registrations between the same two modules, estimated), "
                  "gravity (the run's inclinometer.csv, where it has one), scale (the odometry's "
                  "scale error, estimated), centreline (each instant's pipe axis from its walls, "
                  "tied to a curve whose bending costs); "
                  "`none` keeps the odometry + rig poses")
      ->delimiter(',')
      ->check(CLI::IsMember({"feature", "projection", "texture", "rig", "odometry", "scale",
                             "straightness", "bias", "gravity", "centreline", "none"}))
      ->capture_default_str();
  sub->add_option("--inclinometer-sigma-deg", args->inclinometer_sigma_deg,
                  "σ of one inclinometer reading across gravity, the carrier's own accelerations "
                  "included (the gravity edges' weight)")
      ->capture_default_str()
      ->check(CLI::Range(1e-4, 10.0));
  sub->add_option("--featureless-bend-radius-m", args->featureless_bend_radius_m,
                  "Where no feature edge sees the pipe's turn (plastic), a bend of this radius "
                  "costs χ² 1 per metre of the centreline: the larger, the straighter the pipe is "
                  "held there (a sewer is laid straight between manholes; lower it for a pipe "
                  "laid in a curve)")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 1e9));
  sub->add_flag("--force", args->force,
                "Redo the stage from scratch, also when it was run with other options");
  sub->add_flag("--quiet", args->quiet, "No progress bar");
  return {sub, [args] {
            if (args->edges.size() > 1 &&
                std::find(args->edges.begin(), args->edges.end(), "none") != args->edges.end())
              throw InvalidValue("--edges", "none cannot be combined with other edge types");
            const CaptureRun run = LoadRun(args->run);
            RegisterStageOptions options;
            options.threads = args->threads;
            options.fusion.threads = args->threads;
            options.force = args->force;
            const auto use = [&](const char* type) {
              return std::find(args->edges.begin(), args->edges.end(), type) != args->edges.end();
            };
            options.pairs.feature_registration = use("feature");
            options.pairs.projection_fallback = use("projection");
            options.pairs.projection.photometric.enabled = use("texture");
            options.priors.rig = use("rig");
            options.priors.odometry = use("odometry");
            options.priors.straightness = use("straightness");
            options.fusion.group_biases = use("bias");
            options.fusion.gravity = use("gravity");
            options.fusion.odometry_scale = use("scale");
            options.fusion.gravity_sigma_deg = args->inclinometer_sigma_deg;
            options.fusion.centreline.enabled = use("centreline");
            options.fusion.centreline.featureless_bend_radius_mm =
                1000.0 * args->featureless_bend_radius_m;
            ProgressBar bar(args->quiet);
            auto progress = [&](const std::string& pass, int done, int total) {
              bar.Update("register " + pass, done, total, pass == "pairs" ? "pairs" : "steps");
            };
            RegisterStageReport report;
            try {
              CheckWorkspaceExists(args->out, "register");
              Workspace workspace(args->out, run);
              PrintRunFileChanges(workspace);
              // rgbd outputs not of the run as it is now: registering them gives a model with
              // gaps, or one from another calibration.
              if (const std::string behind = RgbdBehind(run, workspace); !behind.empty()) {
                fmt::print(stderr,
                           "sewer3d: error: register: {}: run `sewer3d rgbd {} --out {}` first "
                           "(or `sewer3d process`)\n",
                           behind, args->run, args->out);
                return 1;
              }
              report = RunRegisterStage(run, workspace, options, progress);
            } catch (const WorkspaceConflict& e) {
              fmt::print(stderr, "sewer3d: error: {}\n", e.what());
              return 2;
            }
            const StageOutcome outcome = RegisterOutcome(report, args->out);
            PrintStageOutcome(outcome);
            if (outcome.ok) fmt::print("wrote {}\n", outcome.output.string());
            if (!outcome.ok) {
              fmt::print(stderr, "sewer3d: error: {}\n", outcome.error);
              return 1;
            }
            return 0;
          }};
}

}  // namespace sewer3d::cli
