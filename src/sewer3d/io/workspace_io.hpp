#pragma once
/// \file
/// `WS/workspace.json` of a processing workspace (DESIGN.md contract "processing workspace";
/// docs/rgbd.md has the format): the run it belongs to, the software version, and per stage
/// the options its outputs were made with and whether it finished. Written atomically; errors
/// are FileError naming the file and field.

#include <filesystem>
#include <map>
#include <string>

#include "sewer3d/io/file_stamp.hpp"

namespace sewer3d {

/// One stage's record ("rgbd", later "register", "model", "inspect").
struct WorkspaceStage {
  /// The options the stage's outputs were made with: a JSON object as compact text with sorted
  /// keys (nlohmann's dump()), compared as text.
  std::string options_json = "{}";
  bool done = false;  ///< every acquisition (or item) finished without failure
  /// An earlier stage's outputs changed after this one was made: its outputs are out of date
  /// (not done) and the next run of the stage starts it afresh.
  bool stale = false;
  std::string started_utc;       ///< ISO 8601, when the outputs now present were begun
  std::string done_utc;          ///< ISO 8601; empty while not done
  std::string software_version;  ///< the version that last ran the stage
  /// Wall time (s) of the invocation that last finished the stage (done or not); 0 before.
  double seconds = 0.0;
  std::map<std::string, std::string> notes;  ///< facts about the outputs, e.g. "color"
  /// The stage's key outputs as it wrote them (path relative to the workspace), recorded when
  /// it ends done: a later stage can tell them from files edited or copied in since.
  std::map<std::string, FileStamp> outputs;
};

/// The whole workspace.json.
struct WorkspaceRecord {
  std::string run;               ///< the capture run's folder, absolute
  std::string software_version;  ///< the version that last wrote the file
  std::map<std::string, WorkspaceStage> stages;
  /// The run's own files the stages were made from (rig.json, its pattern matrices,
  /// acquisitions.csv, odometry.csv), by their path relative to the run folder: a file changed
  /// since makes the stages that use it stale (pipeline/workspace.hpp). Absent in workspaces
  /// written before version 0.1 recorded them.
  std::map<std::string, FileStamp> run_files;
};

/// The JSON text of workspace.json (format "sewer3d-workspace", version 1).
std::string WorkspaceToJson(const WorkspaceRecord& record);
/// Parses workspace.json's text; `path` names the file in errors. Unknown members are kept
/// out of the record but allowed (later versions may add some).
WorkspaceRecord WorkspaceFromJson(const std::string& text, const std::filesystem::path& path);

/// Writes workspace.json atomically (atomic_file.hpp).
void WriteWorkspaceRecord(const std::filesystem::path& path, const WorkspaceRecord& record);
/// Reads workspace.json; FileError when missing or malformed.
WorkspaceRecord ReadWorkspaceRecord(const std::filesystem::path& path);

}  // namespace sewer3d
