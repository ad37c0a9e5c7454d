#pragma once
/// \file
/// A processing workspace (DESIGN.md contract "processing workspace"): the folder `WS` that the
/// stages of `sewer3d process` (rgbd, register, model, inspect) write into, and its record
/// `WS/workspace.json` (io/workspace_io.hpp): which run it belongs to, which software version
/// wrote it, and per stage the options its outputs were made with and whether it is done.
///
/// Re-running a stage: with the options recorded, the stage resumes (work already on disk is
/// kept and skipped); with other options it is refused (WorkspaceConflict) unless forced, and
/// forcing removes the stage's folder and starts the stage afresh. A workspace never changes
/// runs.

#include <chrono>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/workspace_io.hpp"

namespace sewer3d {

struct CaptureRun;

/// Throws FileError naming `folder`/workspace.json when that workspace records another run
/// than `run_folder` (an evaluation compares a workspace with its own run's truth only), or
/// naming `folder` when it holds stage outputs without a record (nothing says what made them);
/// nothing when it has neither.
void CheckWorkspaceOfRun(const std::filesystem::path& folder,
                         const std::filesystem::path& run_folder);

/// Throws FileError naming `folder` when it is the capture run's folder, lies inside it, or
/// holds a run.json: outputs there would mix with the run as captured. `role` names the
/// folder in the message, e.g. "the workspace (--out)".
void CheckOutsideTheRun(const std::filesystem::path& folder,
                        const std::filesystem::path& run_folder, const std::string& role);

/// The first of `owners` (file names such as "run.json", "workspace.json") found as a regular
/// file in a folder above `folder`, or in `folder` itself with `including_folder`, links
/// resolved; empty when none. A workspace or a demo inside a run or another workspace would mix
/// with it (and a --force there would remove it).
std::filesystem::path OwnerAbove(const std::filesystem::path& folder,
                                 std::initializer_list<const char*> owners, bool including_folder);

/// The software version recorded in workspace.json: CMake's PROJECT_VERSION, e.g. "0.1.0".
std::string SoftwareVersion();

/// The stages in the order each uses the outputs of those before it: rgbd, register, model,
/// inspect, report (the chain of `sewer3d process`).
const std::vector<std::string>& WorkspaceStageOrder();

/// The folder under WS a stage writes: its name, but "registration" for register and
/// "inspection" for inspect.
std::string OutputFolderName(const std::string& stage);

/// A stage cannot run in this workspace as asked (another run, other options without force).
/// The message is one line, naming workspace.json and what to do.
class WorkspaceConflict : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One workspace folder, opened for one run. Not thread-safe: stages call it from the thread
/// that runs them.
class Workspace {
 public:
  /// Opens `folder` for the run at `run_folder`: takes the workspace's lock (FileError when
  /// another process holds it), removes temporaries a killed run left, reads
  /// `folder/workspace.json` when it exists (FileError when it is malformed; WorkspaceConflict
  /// when it records another run), else starts a new record, written by the first BeginStage
  /// (WorkspaceConflict when stage output folders are there without a record).
  Workspace(const std::filesystem::path& folder, const std::filesystem::path& run_folder);
  /// As above for the loaded `run`, and then checks the run's own files the stages were made
  /// from against the stamps workspace.json records (rig.json, its pattern matrices and
  /// acquisitions.csv feed rgbd, odometry.csv feeds register): a file changed since marks the
  /// stage it feeds and every later one stale, so that they start afresh, and says so in
  /// run_file_changes(). The new stamps are recorded with the next write of workspace.json.
  Workspace(const std::filesystem::path& folder, const CaptureRun& run);

  const std::filesystem::path& folder() const { return folder_; }
  /// `WS/<stage>`, where the stage writes its files.
  std::filesystem::path StageFolder(const std::string& stage) const { return folder_ / stage; }
  std::filesystem::path RecordFile() const { return folder_ / "workspace.json"; }
  const WorkspaceRecord& record() const { return record_; }
  /// Temporaries of killed runs removed on opening.
  int stale_temporaries_removed() const { return stale_temporaries_removed_; }
  /// One line per run file changed since the stages used it (constructor for a run), naming
  /// the file and the stages that start afresh; empty when nothing changed.
  const std::vector<std::string>& run_file_changes() const { return run_file_changes_; }

  /// Records that `stage` starts with `options_json` (a JSON object as compact text, sorted
  /// keys) and marks it not done; writes workspace.json. When the stage was recorded with
  /// other options: WorkspaceConflict, unless `force`. With `force` (whatever the options)
  /// the stage's folder is removed first, so nothing made before is kept; likewise when the
  /// stage is recorded stale (an earlier stage's outputs changed since it ran), and every later
  /// stage recorded is marked stale.
  void BeginStage(const std::string& stage, const std::string& options_json, bool force);
  /// BeginStage's refusals (a damaged options record, other options without `force`), without
  /// its effects: a stage that works before it can begin checks first, and removes nothing when
  /// that work refuses an option.
  void CheckBeginStage(const std::string& stage, const std::string& options_json, bool force) const;

  /// Records the end of `stage` (begun before): `done` (every item finished without failure)
  /// with the time, the wall time since its BeginStage (`seconds`), and `notes` about its
  /// outputs; writes workspace.json. `changed`: this run changed the stage's outputs, so every
  /// later stage recorded (WorkspaceStageOrder) is marked stale and not done — a resumed
  /// stage that found nothing to do passes false.
  void FinishStage(const std::string& stage, bool done,
                   const std::map<std::string, std::string>& notes, bool changed = true);

  /// The first of `stage`'s key outputs (registration/poses.csv, model/model.json,
  /// inspection/observations.json) that is no longer the file the stage wrote when it ended
  /// done (edited, or copied in from another workspace), as its path; "" when each is as
  /// written, or none was recorded (not done, or a workspace from before outputs were stamped).
  std::string ChangedOutput(const std::string& stage) const;

  /// Records the entry `name` of a command that runs several stages (`process`): the options
  /// it was given, whether every stage ended done, its wall time and notes. Replaces what was
  /// recorded under `name` and is never refused (each stage checks its own options); the
  /// entry has no folder. Writes workspace.json.
  void RecordCommand(const std::string& name, const std::string& options_json, bool done,
                     double seconds, const std::map<std::string, std::string>& notes);

 private:
  void MarkLaterStagesStale(const std::string& stage);
  /// Marks `stage` (if recorded) and every later recorded stage stale and not done; returns the
  /// names of those marked.
  std::vector<std::string> MarkStaleFrom(const std::string& stage);
  void CheckRunFiles(const CaptureRun& run);
  /// Marks the stages from `first_stage` on stale and says so (run_file_changes).
  void NoteRunFileChange(const std::filesystem::path& file, const std::string& what,
                         const std::string& first_stage);

  std::filesystem::path folder_;
  FolderLock lock_;
  int stale_temporaries_removed_ = 0;
  std::vector<std::string> run_file_changes_;
  WorkspaceRecord record_;
  std::map<std::string, std::chrono::steady_clock::time_point> begun_;  ///< by BeginStage
};

}  // namespace sewer3d
