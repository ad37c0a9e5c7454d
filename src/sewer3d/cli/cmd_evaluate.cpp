// `sewer3d evaluate`: its options, and which evaluation runs. plane|cylinder fit the surface to
// a cloud (cmd_evaluate_surface.cpp); rgbd, registration, model and inspection judge a stage
// on a simulated run (cmd_evaluate_rgbd.cpp, cmd_evaluate_registration.cpp, ...).

#include <fmt/core.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/evaluate_commands.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/pipeline/workspace.hpp"
#include "sewer3d/simeval/rgbd_evaluation.hpp"

namespace sewer3d::cli {
namespace {

struct Args {
  std::string surface, cloud, truth, run, workspace, out, captures, module;
  int smoothing_px = RgbdEvaluationOptions{}.colour_smoothing_px;
  double local_alignment_mm = 0.0;
  int stride = 0;
  double inner_fraction = 0.5;
};

constexpr const char* kAllOptions[] = {
    "--cloud",  "--truth",        "--inner-fraction",     "--run",      "--workspace", "--out",
    "--stride", "--smoothing-px", "--local-alignment-mm", "--captures", "--module"};

// The options an evaluation of `kind` takes.
std::vector<std::string> OptionsOf(const std::string& kind) {
  if (kind == "plane" || kind == "cylinder")
    return {"--cloud", "--truth", "--inner-fraction", "--out"};
  if (kind == "calibration") return {"--captures", "--module", "--out"};
  std::vector<std::string> own{"--run", "--workspace", "--out"};
  if (kind == "rgbd") own.emplace_back("--smoothing-px");
  if (kind == "model") own.emplace_back("--stride");
  if (kind == "inspection") own.emplace_back("--local-alignment-mm");
  return own;
}

// An evaluation of a workspace's stage against its run's truth.
int EvaluateWorkspace(const Args& a) {
  if (a.run.empty() || a.workspace.empty())
    throw InvalidValue("--run, --workspace", "evaluate " + a.surface + " needs both");
  CheckWorkspaceOfRun(a.workspace, a.run);
  if (!a.out.empty()) CheckOutsideTheRun(a.out, a.run, "the evaluation's folder (--out)");
  // Not while a stage writes the workspace (half-written outputs), nor two evaluations at once
  // (they write WS/evaluation).
  std::optional<FolderLock> lock;
  std::error_code ec;
  if (std::filesystem::is_directory(a.workspace, ec)) lock.emplace(a.workspace);
  const std::string warning = StageNotDone(a.workspace, a.surface);
  int rc = 0;
  if (a.surface == "rgbd")
    rc = RunEvaluateRgbd(a.run, a.workspace, a.out, a.smoothing_px);
  else if (a.surface == "registration")
    rc = RunEvaluateRegistration(a.run, a.workspace, a.out);
  else if (a.surface == "model")
    rc = RunEvaluateModel(a.run, a.workspace, a.out, a.stride);
  else
    rc = RunEvaluateInspection(a.run, a.workspace, a.local_alignment_mm, a.out);
  // After the result, so that a failure stays one line.
  if (!warning.empty()) fmt::print(stderr, "sewer3d: warning: {}\n", warning);
  return rc;
}

}  // namespace

Command AddEvaluateCommand(CLI::App& app) {
  auto args = std::make_shared<Args>();
  CLI::App* sub =
      app.add_subcommand("evaluate",
                         "Accuracy against the truth: a plane or cylinder fitted to a cloud, a "
                         "processing stage on a simulated run, or a module calibrated from "
                         "simulated captures");
  sub->add_option("KIND", args->surface,
                  "plane, cylinder, rgbd, registration, model, inspection or calibration")
      ->required()
      ->check(CLI::IsMember(
          {"plane", "cylinder", "rgbd", "registration", "model", "inspection", "calibration"}));
  sub->add_option("--captures", args->captures,
                  "calibration: the simulated captures (simulate calibration's --out)");
  sub->add_option("--module", args->module, "calibration: the module calibrate module wrote");
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
      "WS/evaluation/<what>); calibration: the evaluation's JSON file (default: none); plane, "
      "cylinder: folder for residuals.png (and truth_residuals.png with --truth; default: "
      "none)");
  sub->add_option("--local-alignment-mm", args->local_alignment_mm,
                  "inspection: judge each observation against the truth aligned by the cameras "
                  "within ± this of it (a long run whose trajectory one alignment cannot hold); 0: "
                  "one alignment for the run")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6));
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
            // Options of another kind of evaluation are refused, not ignored.
            const std::vector<std::string> own = OptionsOf(args->surface);
            for (const char* name : kAllOptions) {
              if (sub->get_option(name)->count() > 0 &&
                  std::find(own.begin(), own.end(), name) == own.end())
                throw InvalidValue(name, "does not apply to evaluate " + args->surface);
            }
            if (args->surface == "calibration") {
              if (args->captures.empty()) throw CLI::RequiredError("--captures");
              if (args->module.empty()) throw CLI::RequiredError("--module");
              return RunEvaluateCalibration(args->captures, args->module, args->out);
            }
            if (own.front() == "--run") return EvaluateWorkspace(*args);
            if (args->cloud.empty()) throw CLI::RequiredError("--cloud");
            return RunEvaluateSurface(args->surface, args->cloud, args->truth, args->inner_fraction,
                                      args->out);
          }};
}

}  // namespace sewer3d::cli
