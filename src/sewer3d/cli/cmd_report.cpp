// `sewer3d report RUN --out WS`: WS/report/index.html, one self-contained offline page of what
// the workspace holds (docs/report.md).

#include <fmt/core.h>

#include <filesystem>
#include <string>

#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/process_command.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/pipeline/process_chain.hpp"
#include "sewer3d/pipeline/report_stage.hpp"

namespace sewer3d::cli {

Command AddReportCommand(CLI::App& app) {
  struct Args {
    std::string run, out;
    bool quiet = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "report",
      "WS/report/index.html: one self-contained offline page with the run summary, the unrolled "
      "maps, a 3D viewer, the profile, the observations and the accuracy figures");
  sub->add_option("RUN", args->run, "Capture run folder (docs/formats.md)")->required();
  sub->add_option("--out", args->out, "Processing workspace folder WS")->required();
  sub->add_flag("--quiet", args->quiet, "Print only where the report is");
  return {sub, [args] {
            CheckWorkspaceExists(args->out, "report");
            const CaptureRun run = LoadRun(args->run);
            ReportStageReport r;
            try {
              Workspace workspace(args->out, run);
              PrintRunFileChanges(workspace);
              r = RunReportStage(run, workspace, false);
            } catch (const WorkspaceConflict& e) {
              fmt::print(stderr, "sewer3d: error: {}\n", e.what());
              return 2;
            }
            const StageOutcome o = ReportOutcome(r);
            for (const std::string& w : r.warnings) fmt::print(stderr, "sewer3d: warning: {}\n", w);
            if (!r.summary.maps_problem.empty())
              fmt::print(stderr, "sewer3d: warning: report without maps: {}\n",
                         r.summary.maps_problem);
            if (!args->quiet) {
              for (const std::string& note : r.summary.notes) fmt::print("note: {}\n", note);
              fmt::print("{}\n", o.summary);
            }
            fmt::print("wrote {}\n", r.html.string());
            return 0;
          }};
}

}  // namespace sewer3d::cli
