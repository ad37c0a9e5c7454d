// `sewer3d model RUN --out WS`: the pipe model from the registered acquisitions
// (docs/model.md).

#include <fmt/core.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>

#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/process_command.hpp"
#include "sewer3d/cli/progress_bar.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/pipeline/model_stage.hpp"
#include "sewer3d/pipeline/process_chain.hpp"
#include "sewer3d/pipeline/rgbd_inputs.hpp"
#include "sewer3d/pipeline/workspace.hpp"

namespace sewer3d::cli {

void AddModelStageOptions(CLI::App& sub, ModelStageOptions& o) {
  sub.add_option("--resolution-mm", o.resolution_mm, "Map cell size along and around the pipe")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 50.0));
  sub.add_option("--start-station-mm", o.start_station_mm,
                 "Station of the run's first carrier position (where the run began)")
      ->capture_default_str()
      ->check(CLI::Range(-1e7, 1e7));
  sub.add_option("--nominal-diameter-mm", o.nominal_diameter_mm,
                 "Model diameter (the round pipe the displacement is measured from); 0: the "
                 "fitted diameter rounded to 5 mm")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10000.0));
  sub.add_flag("--straight", o.straight, "One straight cylinder instead of a bending centreline");
  sub.add_option("--tile-length-mm", o.tile_length_mm, "Tile along the pipe (bounds memory)")
      ->capture_default_str()
      ->check(CLI::Range(20.0, 10000.0));
  sub.add_option("--pixel-step", o.pixel_step, "Every n-th depth-map pixel into the maps")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  sub.add_option("--hole-edge-band-mm", o.maps.hole_edge_band_mm,
                 "Hole edges at the frames' median within this band; 0: a cell any frame "
                 "measured is kept (the union)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 100.0));
  sub.add_option("--mesh-step-mm", o.displaced.step_mm, "Vertex spacing of mesh.glb")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 1000.0));
  sub.add_flag("!--no-module-offsets", o.module_offsets,
               "Take no range offset off each module's pixels (by default each module's offset "
               "is estimated where its neighbours see the same wall)");
  sub.add_flag("--keep-tiles", o.keep_tiles,
               "Keep WS/model/tiles/ when the whole-run map files are written");
}

Command AddModelCommand(CLI::App& app) {
  struct Args {
    std::string run, out;
    ModelStageOptions options;
    bool quiet = false;
  };
  auto args = std::make_shared<Args>();
  args->options.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  CLI::App* sub = app.add_subcommand(
      "model",
      "The pipe model: WS/model/texture.png, displacement.png/.tiff, coverage.png, model.json, "
      "surface.ply, mesh.obj, mesh.glb (needs WS/registration from `sewer3d register`)");
  sub->add_option("RUN", args->run, "Capture run folder (docs/formats.md)")->required();
  sub->add_option("--out", args->out, "Processing workspace folder WS")->required();
  AddModelStageOptions(*sub, args->options);
  sub->add_option("--threads", args->options.threads, "Tiles made at once")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  sub->add_flag("--force", args->options.force,
                "Redo the stage from scratch, also when it was run with other options");
  sub->add_flag("--quiet", args->quiet, "No progress bar");
  return {sub, [args] {
            try {
              args->options.Check();
            } catch (const InvalidValue& e) {  // in the command line's terms
              throw InvalidValue(e.field() == "start_station_mm" ? "--start-station-mm" : e.field(),
                                 e.problem());
            }
            const CaptureRun run = LoadRun(args->run);
            const double cells =
                std::pow(ModelStageOptions{}.resolution_mm / args->options.resolution_mm, 2);
            if (cells > 1.5) {  // the time and memory grow with the cell count
              fmt::print(
                  "model: {:g} mm cells: {:.0f} times the cells, time and map memory of the "
                  "default {:g} mm\n",
                  args->options.resolution_mm, cells, ModelStageOptions{}.resolution_mm);
              std::fflush(stdout);
            }
            ProgressBar bar(args->quiet);
            auto progress = [&](const std::string& pass, int done, int total) {
              bar.Update("model " + pass, done, total,
                         pass == "samples" ? "acquisitions" : pass.c_str());
            };
            ModelStageReport r;
            std::string behind;  // rgbd outputs older than the run's images
            try {
              CheckWorkspaceExists(args->out, "model");
              Workspace workspace(args->out, run);
              PrintRunFileChanges(workspace);
              behind = RgbdBehind(run, workspace);
              r = RunModelStage(run, workspace, args->options, progress);
            } catch (const WorkspaceConflict& e) {
              fmt::print(stderr, "sewer3d: error: {}\n", e.what());
              return 2;
            } catch (const InvalidValue& e) {  // the stage's check of an option, as a flag
              if (e.field() != "nominal_diameter_mm") throw;
              throw InvalidValue("--nominal-diameter-mm", e.problem());
            }
            const StageOutcome outcome = ModelOutcome(r, args->out);
            PrintStageOutcome(outcome);
            if (!outcome.ok) {
              fmt::print(stderr, "sewer3d: error: {}\n", outcome.error);
              return 1;
            }
            fmt::print("wrote {}, look at {}\n",
                       (std::filesystem::path(args->out) / "model" / "model.json").string(),
                       outcome.output.string());
            if (!behind.empty()) {
              fmt::print(stderr,
                         "sewer3d: warning: {}: the model used what is there; run `sewer3d "
                         "process` to bring every stage up to date\n",
                         behind);
            }
            return 0;
          }};
}

}  // namespace sewer3d::cli
