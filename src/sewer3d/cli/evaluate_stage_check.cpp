// Support of `sewer3d evaluate`: whether the workspace records the evaluated stage as done.

#include <fmt/core.h>

#include "sewer3d/cli/evaluate_commands.hpp"
#include "sewer3d/io/workspace_io.hpp"

namespace sewer3d::cli {

// Evaluating outputs that workspace.json records as stale or not done judges an earlier run of
// the stage, not the one the workspace now stands for: said on stderr, then evaluated.
// The warning that the workspace records the evaluated stage as not done; empty when it is.
std::string StageNotDone(const std::filesystem::path& workspace, const std::string& kind) {
  const std::string stage = kind == "registration" ? "register"
                            : kind == "inspection" ? "inspect"
                                                   : kind;
  const std::filesystem::path record_file = workspace / "workspace.json";
  if (!std::filesystem::is_regular_file(record_file)) return "";
  const WorkspaceRecord record = ReadWorkspaceRecord(record_file);
  const auto it = record.stages.find(stage);
  if (it == record.stages.end() || it->second.done) return "";
  return fmt::format(
      "{}: records the {} stage as {}: evaluated the outputs an earlier run of it left (run "
      "`sewer3d process` to bring it up to date)",
      record_file.string(), stage, it->second.stale ? "stale" : "not done (failed or interrupted)");
}

}  // namespace sewer3d::cli
