// `sewer3d rgbd RUN --out WS`: the RGB-D stage over a whole capture run (docs/rgbd.md).

#include <fmt/core.h>

#include <filesystem>
#include <string>
#include <thread>

#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/process_command.hpp"
#include "sewer3d/cli/progress_bar.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/pipeline/process_chain.hpp"
#include "sewer3d/pipeline/rgbd_stage.hpp"
#include "sewer3d/pipeline/workspace.hpp"

namespace sewer3d::cli {

Command AddRgbdCommand(CLI::App& app) {
  struct Args {
    std::string run, out;
    int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    double max_edge_steps = FrameReconstructionOptions{}.max_edge_steps;
    SpotFlags spots;
    bool quiet = false, force = false, debug_images = false, no_deblur = false;
    int reference_frames = RgbdColourOptions{}.reference_frames;
    std::string correction = "linear";
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "rgbd",
      "RGB-D for every acquisition of a run: WS/rgbd/m<k>/<counter>_color.png (corrected "
      "texture at the pattern instant), _depth.tiff, _cloud.ply, _report.json");
  sub->add_option("RUN", args->run, "Capture run folder (docs/formats.md)")->required();
  sub->add_option("--out", args->out, "Processing workspace folder WS")->required();
  sub->add_option("--threads", args->threads, "Acquisitions processed at once")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  sub->add_option("--max-edge-steps", args->max_edge_steps,
                  "Depth map: longest triangle edge, in pattern pitches")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 20.0));
  AddSpotFlags(sub, &args->spots);
  sub->add_option("--reference-frames", args->reference_frames,
                  "Acquisitions per module the reference light (shading correction) is estimated "
                  "from")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  sub->add_option("--correction", args->correction,
                  "Shading and colour correction: linear (per-channel division by the reference "
                  "light) or lab (the paper's: L* from the reference's lightness, its a*/b* cast "
                  "removed)")
      ->capture_default_str()
      ->check(CLI::IsMember({"lab", "linear"}));
  sub->add_flag("--no-deblur", args->no_deblur, "Leave the texture images' motion blur as it is");
  sub->add_flag("--debug-images", args->debug_images,
                "Also write WS/rgbd/debug/m<k>/<counter>_captured.png, _mapped.png, "
                "_deblur_crop.png");
  sub->add_flag("--force", args->force,
                "Redo the stage from scratch, also when it was run with other options");
  sub->add_flag("--quiet", args->quiet, "No progress bar");
  return {sub, [args] {
            const CaptureRun run = LoadRun(args->run);
            RgbdStageOptions options;
            options.reconstruction.max_edge_steps = args->max_edge_steps;
            args->spots.ApplyTo(options.reconstruction);
            options.threads = args->threads;
            options.colour.reference_frames = args->reference_frames;
            options.colour.deblur = !args->no_deblur;
            options.colour.correction.space =
                args->correction == "lab" ? CorrectionSpace::kLab : CorrectionSpace::kLinear;
            options.colour.debug_images = args->debug_images;
            options.force = args->force;
            ProgressBar bar(args->quiet);
            auto progress = [&](const std::string& pass, int done, int total) {
              bar.Update("rgbd " + pass, done, total, "acquisitions");
            };
            RgbdStageReport report;
            try {
              Workspace workspace(args->out, run);
              PrintRunFileChanges(workspace);
              report = RunRgbdStage(run, workspace, options, progress);
            } catch (const WorkspaceConflict& e) {
              fmt::print(stderr, "sewer3d: error: {}\n", e.what());
              return 2;
            }
            const StageOutcome outcome = RgbdOutcome(report, args->out);
            PrintStageOutcome(outcome);
            if (args->debug_images && report.skipped > 0) {
              fmt::print(
                  stderr,
                  "sewer3d: warning: rgbd: --debug-images: {} acquisitions were done by an earlier "
                  "run and got no debug images (add --force to redo them)\n",
                  report.skipped);
            }
            fmt::print("wrote {}\n", outcome.output.string());
            if (!outcome.ok) {
              fmt::print(stderr, "sewer3d: error: {}\n", outcome.error);
              return 1;
            }
            return 0;
          }};
}

}  // namespace sewer3d::cli
