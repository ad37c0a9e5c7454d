// `sewer3d inspect RUN --out WS`: EN 13508-2 observations and the cross-section profile from the
// pipe model (docs/inspection.md).

#include <fmt/core.h>

#include <filesystem>
#include <string>

#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/process_command.hpp"
#include "sewer3d/cli/progress_bar.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/pipeline/inspect_stage.hpp"
#include "sewer3d/pipeline/process_chain.hpp"
#include "sewer3d/pipeline/workspace.hpp"

namespace sewer3d::cli {

void AddInspectStageOptions(CLI::App& sub, InspectStageOptions& o) {
  InspectOptions& i = o.inspect;
  sub.add_option("--nominal-diameter-mm", i.nominal_diameter_mm,
                 "DN the percentages refer to; 0: the model's diameter")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10000.0));
  sub.add_option("--min-offset-mm", i.joints.min_offset_mm,
                 "A joint without an open gap is found from this radial offset")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 1000.0));
  sub.add_option("--intrusion-mm", i.defects.intrusion_mm,
                 "Regions standing this far into the pipe are observations")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 1000.0));
  sub.add_option("--surface-mm", i.defects.surface_mm,
                 "Regions this deep into the wall (spalling, cracks) are observations")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 1000.0));
  sub.add_option("--crack-min-length-mm", i.cracks.min_length_mm,
                 "A dark line in the texture this long is a crack (BAB)")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 100000.0));
  sub.add_flag("!--no-texture-cracks", i.cracks.enabled,
               "Do not search the texture for cracks (only the displacement map)");
  sub.add_option("--min-deformation-pct", i.min_deformation_pct,
                 "A section whose diameter is reduced by this much is deformed (BAA)")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 100.0));
  sub.add_option("--profile-step-mm", o.profile.step_mm, "Profile row spacing (profile.csv)")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 10000.0));
}

Command AddInspectCommand(CLI::App& app) {
  struct Args {
    std::string run, out;
    InspectStageOptions options;
    bool quiet = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "inspect",
      "EN 13508-2 observations and the profile: WS/inspection/observations.json/.csv/.xml, "
      "profile.csv, crops/ (needs WS/model from `sewer3d model`)");
  sub->add_option("RUN", args->run, "Capture run folder (docs/formats.md)")->required();
  sub->add_option("--out", args->out, "Processing workspace folder WS")->required();
  AddInspectStageOptions(*sub, args->options);
  sub->add_flag("--force", args->options.force,
                "Redo the stage from scratch, also when it was run with other options");
  sub->add_flag("--quiet", args->quiet, "No progress bar");
  return {sub, [args] {
            args->options.Check();
            const CaptureRun run = LoadRun(args->run);
            ProgressBar bar(args->quiet);
            auto progress = [&](const std::string& pass, int done, int total) {
              bar.Update("inspect " + pass, done, total, "pieces");
            };
            InspectStageReport r;
            try {
              CheckWorkspaceExists(args->out, "inspect");
              Workspace workspace(args->out, run);
              PrintRunFileChanges(workspace);
              r = RunInspectStage(run, workspace, args->options, progress);
            } catch (const WorkspaceConflict& e) {
              fmt::print(stderr, "sewer3d: error: {}\n", e.what());
              return 2;
            } catch (const InvalidValue& e) {  // the stage's check of an option, as a flag
              if (e.field() != "nominal_diameter_mm") throw;
              throw InvalidValue("--nominal-diameter-mm", e.problem());
            }
            const StageOutcome outcome = InspectOutcome(r, args->out);
            fmt::print("{}\nwrote {}\n", outcome.summary, outcome.output.string());
            return 0;
          }};
}

}  // namespace sewer3d::cli
