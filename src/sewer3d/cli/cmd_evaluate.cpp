// `sewer3d evaluate`: its options, and which evaluation runs. plane|cylinder fit the surface to
// a cloud (cmd_evaluate_surface.cpp); rgbd, registration, model and inspection judge a stage
// on a simulated run (cmd_evaluate_rgbd.cpp, cmd_evaluate_registration.cpp, ...).

#include <fmt/core.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/evaluate_commands.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/workspace_io.hpp"
#include "sewer3d/pipeline/workspace.hpp"
#include "sewer3d/simeval/rgbd_evaluation.hpp"

namespace sewer3d::cli {
namespace {

// Evaluating outputs that workspace.json records as stale or not done judges an earlier run of
// the stage, not the one the workspace now stands for: said on stderr, then evaluated.
void WarnOfStageNotDone(const std::filesystem::path& workspace, const std::string& kind) {
  const std::string stage = kind == "registration" ? "register"
                            : kind == "inspection" ? "inspect"
                                                   : kind;
  const std::filesystem::path record_file = workspace / "workspace.json";
  if (!std::filesystem::is_regular_file(record_file)) return;
  const WorkspaceRecord record = ReadWorkspaceRecord(record_file);
  const auto it = record.stages.find(stage);
  if (it == record.stages.end() || it->second.done) return;
  fmt::print(stderr,
             "sewer3d: warning: {}: records the {} stage as {}: evaluating the outputs an earlier "
             "run of it left (run `sewer3d process` to bring it up to date)\n",
             record_file.string(), stage,
             it->second.stale ? "stale" : "not done (failed or interrupted)");
}

}  // namespace

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
  sub->add_option("KIND", args->surface, "plane, cylinder, rgbd, registration, model or inspection")
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
                  "rgbd, registration, model, inspection: the processing workspace WS")
      ->check(CLI::Validator(
          [](std::string& s) {
            std::error_code ec;
            return std::filesystem::exists(s, ec) && !std::filesystem::is_directory(s, ec)
                       ? s + " is a file; give the workspace folder (the --out of process)"
                       : std::string();
          },
          "WS"));
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
            std::vector<std::string> others =
                of_workspace ? std::vector<std::string>{"--cloud", "--truth", "--inner-fraction"}
                             : std::vector<std::string>{"--run", "--workspace", "--out", "--stride",
                                                        "--smoothing-px"};
            if (of_workspace && args->surface != "rgbd") others.emplace_back("--smoothing-px");
            if (of_workspace && args->surface != "model") others.emplace_back("--stride");
            for (const std::string& name : others) {
              if (sub->get_option(name)->count() > 0) {
                throw InvalidValue(name, "does not apply to evaluate " + args->surface);
              }
            }
            if (of_workspace && !args->run.empty() && !args->workspace.empty()) {
              CheckWorkspaceOfRun(args->workspace, args->run);
              WarnOfStageNotDone(args->workspace, args->surface);
            }
            if (of_workspace && !args->run.empty() && !args->out.empty())
              CheckOutsideTheRun(args->out, args->run, "the evaluation's folder (--out)");
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
            return RunEvaluateSurface(args->surface, args->cloud, args->truth,
                                      args->inner_fraction);
          }};
}

}  // namespace sewer3d::cli
