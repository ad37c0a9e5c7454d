#pragma once
/// \file
/// `sewer3d process` (DESIGN.md contracts "processing workspace" and "command line";
/// docs/process.md): the stages of the processing chain run in order over one capture run into
/// one workspace. Each stage resumes by itself (it skips the work on disk); on top of that, a
/// stage that workspace.json records as done with the same options, after earlier stages that
/// had nothing to do, is skipped without being started. The first stage that fails stops the
/// chain; what it and the stages before it wrote stays.
///
/// The chain is a list (ProcessStages): a later stage joins with one entry. Options that only
/// later stages use (the model's start station and grid) are recorded now under the `process`
/// entry of workspace.json.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "sewer3d/pipeline/inspect_stage.hpp"
#include "sewer3d/pipeline/model_stage.hpp"
#include "sewer3d/pipeline/register_stage.hpp"
#include "sewer3d/pipeline/report_stage.hpp"
#include "sewer3d/pipeline/rgbd_stage.hpp"
#include "sewer3d/pipeline/workspace.hpp"
#include "sewer3d/run/capture_run.hpp"

namespace sewer3d {

struct ProcessOptions {
  RgbdStageOptions rgbd;              ///< its threads and force are set from the fields below
  RegisterStageOptions registration;  ///< likewise (and its fusion's threads)
  ModelStageOptions model;            ///< likewise, and its resolution and start station
  InspectStageOptions inspect;        ///< likewise (force)
  /// Where the run began along the pipe (mm): the model's station 0 is the carrier centre at
  /// the run's first image plus this (DESIGN.md, model maps). Any finite value.
  double start_station_mm = 0.0;
  double resolution_mm = 0.2;  ///< the model maps' cell size (mm), 0.01..50
  int threads = 1;             ///< workers of every stage (≥ 1); does not change the outputs
  bool force = false;          ///< redo every stage from scratch (Workspace::BeginStage)
  /// Throws std::invalid_argument naming the option (the stages' own Check() too).
  void Check() const;
};

/// What one stage run by the chain came to, in words for people (one line each).
struct StageOutcome {
  bool ok = true;                    ///< false: the stage could not do its task (exit code 1)
  std::string summary;               ///< what it did, with counts
  std::vector<std::string> details;  ///< further lines (e.g. acquisitions left out)
  std::string error;                 ///< !ok: why, naming the file to look at
  std::filesystem::path output;      ///< the file to look at first
};

/// The RGB-D and registration stages' reports in words (also for `sewer3d rgbd|register`).
StageOutcome RgbdOutcome(const RgbdStageReport& report, const std::filesystem::path& workspace);
StageOutcome RegisterOutcome(const RegisterStageReport& report,
                             const std::filesystem::path& workspace);
StageOutcome ModelOutcome(const ModelStageReport& report, const std::filesystem::path& workspace);
StageOutcome InspectOutcome(const InspectStageReport& report,
                            const std::filesystem::path& workspace);
/// The report is always written; a page without maps is a warning line in `details`.
StageOutcome ReportOutcome(const ReportStageReport& report);

/// One stage of the chain. `options_json` is what the stage records in workspace.json (to
/// tell whether the record is current); `run` runs it (with `options.threads` and
/// `options.force` applied), reporting progress with the stage's own pass names.
struct ProcessStage {
  std::string name;  ///< as recorded in workspace.json: "rgbd", "register", …
  std::function<std::string(const ProcessOptions&)> options_json;
  std::function<StageOutcome(const CaptureRun&, Workspace&, const ProcessOptions&,
                             const StageProgress&)>
      run;
  /// Its main output, relative to the workspace: a stage recorded done without it is redone.
  std::string output;
  /// When set, a stage recorded done is redone unless this says its inputs are as it left
  /// them (rgbd: the run's images, added or replaced since).
  std::function<bool(const CaptureRun&, const Workspace&)> up_to_date;
};

/// The chain in order: rgbd, register, model, inspect, report.
const std::vector<ProcessStage>& ProcessStages();

/// One stage as the chain met it.
struct ProcessStageResult {
  std::string name;
  bool skipped = false;  ///< recorded done with these options; not started
  double seconds = 0.0;  ///< wall time now (skipped: what workspace.json recorded)
  StageOutcome outcome;  ///< skipped: ok, summary says so
};

struct ProcessReport {
  std::vector<ProcessStageResult> stages;  ///< those met, in order; a failed one is last
  double seconds = 0.0;                    ///< the whole chain now
  bool ok = true;                          ///< every stage ok
  /// The failed stage, or null.
  const ProcessStageResult* Failure() const;
};

/// The `process` entry's options (compact JSON, sorted keys): resolution_mm,
/// start_station_mm and the stages' names.
std::string ProcessOptionsJson(const ProcessOptions& options);

/// Called once per stage met, after it ended or was skipped.
using StageFinished = std::function<void(const ProcessStageResult&)>;

/// Runs ProcessStages() over `run` into `workspace`. `progress` gets "<stage> <pass>" with
/// each stage's own counts. Throws what the stages throw (std::invalid_argument on invalid
/// options, WorkspaceConflict, FileError); a stage that fails without throwing ends the chain
/// with report.ok false.
ProcessReport RunProcess(const CaptureRun& run, Workspace& workspace, const ProcessOptions& options,
                         const StageProgress& progress = {}, const StageFinished& finished = {});

}  // namespace sewer3d
