#include "sewer3d/report/workspace_inputs.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/io/workspace_io.hpp"

namespace sewer3d {
namespace {

std::string FactText(const nlohmann::json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_float()) return fmt::format("{:.4g}", v.get<double>());
  return v.dump();
}

void AddRunFacts(const std::filesystem::path& run_folder, ReportInputs& in) {
  const std::filesystem::path path = run_folder / "run.json";
  if (!IsRegularFile(path)) {
    in.notes.push_back("No run summary: " + path.string() + " was not found.");
    return;
  }
  const nlohmann::json j = nlohmann::json::parse(ReadTextFile(path), nullptr, false);
  if (!j.is_object()) {
    in.notes.push_back("No run summary: " + path.string() + " is not a JSON object.");
    return;
  }
  for (const char* key : {"created_by", "scenario", "modules", "acquisitions", "images", "complete",
                          "color_filter", "seed"}) {
    if (j.contains(key)) in.run_facts.emplace_back(key, FactText(j[key]));
  }
}

void AddStages(const std::filesystem::path& ws, ReportInputs& in) {
  const std::filesystem::path path = ws / "workspace.json";
  try {
    const WorkspaceRecord record = ReadWorkspaceRecord(path);
    for (const auto& [name, stage] : record.stages)
      in.stages.push_back({name, stage.seconds, stage.done});
  } catch (const FileError& e) {
    in.notes.push_back(std::string("No stage times: ") + e.what());
  }
}

void AddEvaluations(const std::filesystem::path& ws, ReportInputs& in) {
  const std::filesystem::path dir = ws / "evaluation";
  std::error_code error;
  if (!std::filesystem::is_directory(dir, error)) return;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir, error)) {
    if (IsRegularFile(entry.path() / "evaluation.json"))
      files.push_back(entry.path() / "evaluation.json");
  }
  std::sort(files.begin(), files.end());
  for (const auto& f : files)
    in.evaluations.push_back({f.parent_path().filename().string(), ReadTextFile(f)});
}

}  // namespace

ReportInputs GatherReportInputs(const std::filesystem::path& ws,
                                const std::filesystem::path& run_folder) {
  std::error_code error;
  if (!std::filesystem::is_directory(ws, error)) throw FileError(ws, "workspace folder not found");
  ReportInputs in;
  in.model_dir = ws / "model";
  in.run_folder = std::filesystem::absolute(run_folder).lexically_normal().string();
  AddRunFacts(run_folder, in);
  AddStages(ws, in);
  AddEvaluations(ws, in);
  return in;
}

}  // namespace sewer3d
