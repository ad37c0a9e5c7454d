// `sewer3d process RUN --out WS`: every stage of the processing chain in order (docs/process.md).

#include <fmt/core.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/process_command.hpp"
#include "sewer3d/cli/progress_bar.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/pipeline/workspace.hpp"

namespace sewer3d::cli {
namespace {

// The unit of a pass's counts ("rgbd geometry" counts acquisitions, "register pairs" pairs,
// "model tiles" tiles).
const char* PassUnit(const std::string& pass) {
  const std::string last = pass.substr(pass.rfind(' ') + 1);
  if (last == "pairs") return "pairs";
  if (last == "reference") return "modules";
  if (last == "walls") return "steps";
  if (last == "tiles" || last == "meshes") return last == "tiles" ? "tiles" : "meshes";
  if (last == "maps" || last == "crops") return "pieces";  // of the model, as inspect counts
  return "acquisitions";
}

void PrintStage(const ProcessStageResult& r) {
  PrintStageOutcome(r.outcome);
  if (r.skipped)
    fmt::print("{}: {:.1f} s when it was done\n", r.name, r.seconds);
  else if (r.outcome.ok)
    fmt::print("{}: {:.1f} s; wrote {}\n", r.name, r.seconds, r.outcome.output.string());
  else
    fmt::print("{}: {:.1f} s; failed\n", r.name, r.seconds);
  std::fflush(stdout);  // before the next stage's progress on stderr
}

}  // namespace

void PrintStageOutcome(const StageOutcome& outcome) {
  fmt::print("{}\n", outcome.summary);
  std::fflush(stdout);
  const std::string warning = "warning: ";
  for (const std::string& line : outcome.details) {
    if (line.rfind(warning, 0) == 0)
      fmt::print(stderr, "sewer3d: {}\n", line);
    else
      fmt::print("{}\n", line);
  }
}

void PrintRunFileChanges(const Workspace& workspace) {
  for (const std::string& line : workspace.run_file_changes()) fmt::print("{}\n", line);
  std::fflush(stdout);
}

int RunProcessCommand(const ProcessArgs& args, ProcessReport* report_out) {
  ProcessOptions options;
  options.start_station_mm = args.start_station_mm;
  options.resolution_mm = args.resolution_mm;
  options.threads = args.threads;
  args.spots.ApplyTo(options.rgbd.reconstruction);
  options.force = args.force;
  try {
    options.Check();
  } catch (const InvalidValue& e) {  // in the command line's terms
    const std::string field = e.field() == "start_station_mm" ? "--start-station-mm"
                              : e.field() == "resolution_mm"  ? "--resolution-mm"
                                                              : e.field();
    throw InvalidValue(field, e.problem());
  }
  const CaptureRun run = LoadRun(args.run);
  ProgressBar bar(args.quiet);
  auto progress = [&](const std::string& pass, int done, int total) {
    bar.Update(pass, done, total, PassUnit(pass));
  };
  ProcessReport report;
  try {
    Workspace workspace(args.out, run);
    PrintRunFileChanges(workspace);
    report = RunProcess(run, workspace, options, progress, PrintStage);
  } catch (const WorkspaceConflict& e) {
    fmt::print(stderr, "sewer3d: error: {}\n", e.what());
    return 2;
  }
  std::string times;
  for (const ProcessStageResult& r : report.stages)
    times += fmt::format("{} {:.1f} s{}, ", r.name, r.seconds, r.skipped ? " (before)" : "");
  fmt::print("process: {}{:.1f} s in all now; wrote {}\n", times, report.seconds,
             (std::filesystem::path(args.out) / "workspace.json").string());
  if (report_out != nullptr) *report_out = report;
  if (const ProcessStageResult* failed = report.Failure()) {
    fmt::print(stderr, "sewer3d: error: {}: {}\n", failed->name, failed->outcome.error);
    return 1;
  }
  return 0;
}

Command AddProcessCommand(CLI::App& app) {
  auto args = std::make_shared<ProcessArgs>();
  CLI::App* sub = app.add_subcommand("process",
                                     "The whole processing chain over a capture run (rgbd, "
                                     "register, model): WS/workspace.json and "
                                     "each stage's folder; resumes where an earlier run stopped");
  sub->add_option("RUN", args->run, "Capture run folder (docs/formats.md)")->required();
  sub->add_option("--out", args->out, "Processing workspace folder WS")->required();
  sub->add_option("--start-station-mm", args->start_station_mm,
                  "Station of the carrier centre at the run's first image (mm along the pipe); "
                  "recorded for the model stage")
      ->capture_default_str()
      ->check(CLI::Range(-1e7, 1e7));
  sub->add_option("--resolution-mm", args->resolution_mm,
                  "Cell size of the model maps (mm); recorded for the model stage")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 50.0));
  sub->add_option("--threads", args->threads, "Workers of every stage")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  AddSpotFlags(sub, &args->spots);
  sub->add_flag("--force", args->force,
                "Redo every stage from scratch, also those run with other options");
  sub->add_flag("--quiet", args->quiet, "No progress bar");
  return {sub, [args] { return RunProcessCommand(*args); }};
}

}  // namespace sewer3d::cli
