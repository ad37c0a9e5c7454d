#pragma once
/// \file
/// `sewer3d process RUN --out WS` (docs/process.md), shared with `sewer3d demo`.

#include <CLI/CLI.hpp>
#include <string>
#include <thread>

#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/pipeline/process_chain.hpp"

namespace sewer3d::cli {

struct ProcessArgs {
  std::string run, out;
  double start_station_mm = ProcessOptions{}.start_station_mm;
  double resolution_mm = ProcessOptions{}.resolution_mm;
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  SpotFlags spots;  ///< the rgbd stage's --faint-spots, --no-lost-spots
  bool force = false, quiet = false;
};

/// Runs the chain of stages over args.run into args.out with one progress display, printing
/// each stage's summary and time as it ends and the times of all at the end; fills `report`
/// when given. Returns the exit code: 0, 1 when a stage failed (its error on stderr), 2 when
/// the workspace refuses (another run, other options without --force). Other errors throw.
int RunProcessCommand(const ProcessArgs& args, ProcessReport* report = nullptr);

/// Prints a stage's summary on stdout and its detail lines after it: those that are warnings
/// ("warning: …") go to stderr as `sewer3d: warning: …`, the others to stdout.
void PrintStageOutcome(const StageOutcome& outcome);

/// Prints on stdout what the workspace found changed in the run's own files since its stages
/// used them (Workspace::run_file_changes: which stages start afresh).
void PrintRunFileChanges(const Workspace& workspace);

}  // namespace sewer3d::cli
