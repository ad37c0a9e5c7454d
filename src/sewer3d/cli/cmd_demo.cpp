// `sewer3d demo [--out DIR]`: the product in a few minutes (docs/process.md): simulates the
// compact run, processes it and judges the stages against the run's truth.

#include <fmt/core.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <utility>

#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/demo_summary.hpp"
#include "sewer3d/cli/evaluate_commands.hpp"
#include "sewer3d/cli/process_command.hpp"
#include "sewer3d/cli/simulate_commands.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/pipeline/parallel_items.hpp"
#include "sewer3d/pipeline/report_stage.hpp"
#include "sewer3d/pipeline/workspace.hpp"
#include "sewer3d/simeval/rgbd_evaluation.hpp"

namespace sewer3d::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr const char* kPreset = "compact";

struct DemoArgs {
  std::string out = "sewer3d-demo";
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  bool force = false, quiet = false;
};

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A run this command simulated before and finished (run.json says complete).
bool CompleteDemoRun(const fs::path& run) {
  if (!IsRegularFile(run / "run.json")) return false;
  const RunInfo info = ReadRunInfo(run / "run.json");
  return info.complete && info.scenario == kPreset;
}

// Simulates the compact run into `run` unless a complete one is there (`simulated`: whether it
// did); returns the exit code.
int SimulateUnlessDone(const fs::path& run, const DemoArgs& a, bool& simulated) {
  simulated = false;
  if (!a.force && CompleteDemoRun(run)) {
    fmt::print("simulate: {} holds the complete '{}' run; reused (--force simulates afresh)\n",
               run.string(), kPreset);
    return 0;
  }
  // A simulation of this preset cut short goes on from the images it finished; another run
  // the simulator made is replaced, a real capture refused (SimulateRun).
  RunArgs args;
  args.preset = kPreset;
  args.out = run.string();
  args.quiet = a.quiet;
  args.restart = a.force;
  tbb::task_arena arena(AllowedThreads(a.threads));
  simulated = true;
  return arena.execute([&] { return RunRun(args); });
}

int RunDemo(const DemoArgs& a) {
  const auto start = Clock::now();
  const fs::path dir = a.out, run = dir / "run", ws = dir / "ws";
  CheckDemoFolder(dir);
  fmt::print(
      "== simulate: the '{}' run (0.56 m of DN300, 648 x 486 images, errors of real modules: "
      "realism paper) into {}\n",
      kPreset, run.string());
  std::fflush(stdout);
  bool simulated = false;
  if (const int rc = SimulateUnlessDone(run, a, simulated); rc != 0) return rc;
  const double simulate_s = SecondsSince(start);

  fmt::print("\n== process: {} into {}\n", run.string(), ws.string());
  std::fflush(stdout);
  ProcessArgs process;
  process.run = run.string();
  process.out = ws.string();
  process.threads = a.threads;
  // A run simulated now replaces the one the workspace was made from.
  process.force = a.force || simulated;
  process.quiet = a.quiet;
  ProcessReport report;
  if (const int rc = RunProcessCommand(process, &report); rc != 0) return rc;

  fmt::print("\n== evaluate: the stages against the run's truth\n");
  std::fflush(stdout);
  const auto evaluate_start = Clock::now();
  RunEvaluateRgbd(run.string(), ws.string(), "", RgbdEvaluationOptions{}.colour_smoothing_px);
  RunEvaluateRegistration(run.string(), ws.string(), "");
  RunEvaluateModel(run.string(), ws.string(), "", 0);
  RunEvaluateInspection(run.string(), ws.string(), 0.0, "");
  const double evaluate_s = SecondsSince(evaluate_start);
  // The report again, now with the accuracy section the evaluations wrote.
  const CaptureRun loaded = LoadRun(run);
  Workspace workspace(ws, loaded);
  const ReportStageReport page = RunReportStage(loaded, workspace, false);

  std::string times = fmt::format("simulate {:.1f} s{}", simulate_s, simulated ? "" : " (reused)");
  for (const ProcessStageResult& r : report.stages)
    times += fmt::format(", {} {:.1f} s{}", r.name, r.seconds, r.skipped ? " (done before)" : "");
  fmt::print(
      "\n== demo: done in {:.1f} s ({} threads; peak memory {:.2f} GB): {}, evaluate {:.1f} s\n",
      SecondsSince(start), a.threads, PeakMemoryGb(), times, evaluate_s);
  PrintLookAt(dir, page.html);
  return 0;
}

}  // namespace

Command AddDemoCommand(CLI::App& app) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* sub = app.add_subcommand(
      "demo",
      "Simulate the compact run (0.56 m of DN300: concrete, displaced joint, intruding "
      "connection, plastic), process it and evaluate it against its truth: DIR/run, DIR/ws");
  sub->add_option("--out", args->out, "Folder of the demo: DIR/run, DIR/ws")->capture_default_str();
  sub->add_option("--threads", args->threads, "Workers for simulating and processing")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  sub->add_flag("--force", args->force, "Simulate and process afresh, reusing nothing");
  sub->add_flag("--quiet", args->quiet, "No progress bars");
  return {sub, [args] { return RunDemo(*args); }};
}

}  // namespace sewer3d::cli
