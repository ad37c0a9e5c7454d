// The checks of output paths that argument_checks.hpp declares: not inside a capture run or a
// processing workspace, not over a module's pattern matrix or its description, a workspace
// that a later stage continues must exist, and the demo's folder is its own.

#include <nlohmann/json.hpp>

#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/pipeline/workspace.hpp"

namespace sewer3d::cli {

void CheckNotInRunOrWorkspace(const std::filesystem::path& folder, const char* flag) {
  const auto owner = OwnerAbove(folder, {"run.json", "workspace.json"}, true);
  if (owner.empty()) return;
  if (owner.filename() == "run.json") {
    throw InvalidValue(flag, folder.string() + " lies in the capture run " +
                                 owner.parent_path().string() +
                                 ": outputs there would mix with the run as captured; choose "
                                 "another folder");
  }
  throw InvalidValue(flag, folder.string() + " lies in the processing workspace " +
                               owner.parent_path().string() +
                               ": outputs there would replace or mix with its stages' files; "
                               "choose another folder");
}

void CheckFileNotInRunOrWorkspace(const std::filesystem::path& file, const char* flag) {
  const std::filesystem::path folder = file.parent_path();
  CheckNotInRunOrWorkspace(folder.empty() ? std::filesystem::path(".") : folder, flag);
}

void CheckNotAModulesMatrix(const std::filesystem::path& out) {
  if (out.filename() != "pattern.png") return;
  const std::filesystem::path folder = out.has_parent_path() ? out.parent_path() : ".";
  for (const char* owner : {"module.json", "rig.json"}) {
    if (IsRegularFile(folder / owner)) {
      throw InvalidValue("--out", out.string() + " is the pattern matrix of the " +
                                      (folder / owner).string() +
                                      " beside it; write the new pattern elsewhere");
    }
  }
}

void CheckNotAModuleFile(const std::filesystem::path& out, const char* flag,
                         const std::string& writes) {
  constexpr std::uintmax_t kMaxModuleBytes = 1 << 20;  // a module file is a few kB
  if (!IsRegularFile(out)) return;
  bool module = out.filename() == "module.json";
  std::error_code ec;
  if (!module && std::filesystem::file_size(out, ec) < kMaxModuleBytes && !ec) {
    const nlohmann::json j = nlohmann::json::parse(ReadTextFile(out), nullptr, false);
    module = j.is_object() && j.contains("projector");
  }
  if (!module) return;
  throw InvalidValue(flag, out.string() + " is a module description; this command writes " +
                               writes + ", which would replace it: write it elsewhere");
}

void CheckWorkspaceExists(const std::filesystem::path& folder, const std::string& stage) {
  if (std::filesystem::is_directory(folder)) return;
  throw FileError(folder, "workspace folder not found: `sewer3d " + stage +
                              "` continues the workspace of `sewer3d rgbd` (or of `sewer3d "
                              "process`); is --out mistyped?");
}

void CheckDemoFolder(const std::filesystem::path& dir) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
    throw InvalidValue("--out", dir.string() + " is a file; the demo needs a folder");
  if (const auto owner = OwnerAbove(dir, {"run.json", "workspace.json"}, true); !owner.empty()) {
    throw InvalidValue("--out", dir.string() + " lies in " + owner.string() +
                                    "'s folder; the demo needs a folder of its own");
  }
  // A workspace of another run there would be refused only after the simulation.
  CheckWorkspaceOfRun(dir / "ws", dir / "run");
}

}  // namespace sewer3d::cli
