#include "sewer3d/pipeline/report_stage.hpp"

#include <fmt/core.h>

#include <chrono>
#include <nlohmann/json.hpp>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/inspection_io.hpp"
#include "sewer3d/io/model_io.hpp"
#include "sewer3d/report/workspace_inputs.hpp"

namespace sewer3d {
namespace {

// Recorded, but not done: its outputs (if any) are not those of the stages before it.
bool NotDone(const Workspace& workspace, const char* stage) {
  const auto it = workspace.record().stages.find(stage);
  return it != workspace.record().stages.end() && !it->second.done;
}

bool Done(const Workspace& workspace, const char* stage) {
  const auto it = workspace.record().stages.find(stage);
  return it != workspace.record().stages.end() && it->second.done;
}

// A file a stage recorded as done writes, gone since: the report would show the stage's results
// as empty.
void CheckStageFile(const Workspace& workspace, const char* stage,
                    const std::filesystem::path& file) {
  if (Done(workspace, stage) && !std::filesystem::exists(file)) {
    throw FileError(file, std::string("missing, though workspace.json records the ") + stage +
                              " stage as done: run `sewer3d " + stage + "` again with --force");
  }
}

// Observations must lie on the model they were found on: one far beyond its stations (a hand
// edit, or another model's observations.json) would be listed as this pipe's.
void CheckObservationStations(const std::vector<Observation>& observations,
                              const std::filesystem::path& model_json,
                              const std::filesystem::path& observations_json) {
  constexpr double kMarginMm = 100.0;  // an observation's centre may lie past the last cell
  if (observations.empty() || !std::filesystem::exists(model_json)) return;
  MapGrid grid;
  try {
    grid = ReadModelJson(model_json).grid;
  } catch (const FileError&) {
    return;  // the page says the model cannot be read
  }
  const double first = grid.station0_mm, last = grid.station0_mm + grid.rows * grid.resolution_mm;
  for (const Observation& o : observations) {
    if (o.station_mm >= first - kMarginMm && o.station_mm <= last + kMarginMm) continue;
    throw FileError(observations_json,
                    fmt::format("observation {}: station_mm {:g} lies outside the model's stations "
                                "{:.1f} to {:.1f} mm ({}): edited, or another model's? run "
                                "`sewer3d inspect` again with --force",
                                o.id, o.station_mm, first, last, model_json.string()));
  }
}

}  // namespace

ReportStageReport RunReportStage(const CaptureRun& run, Workspace& workspace, bool force) {
  const auto start = std::chrono::steady_clock::now();
  workspace.BeginStage("report", "{}", force);
  const std::filesystem::path ws = workspace.folder();
  ReportInputs in = GatherReportInputs(ws, run.folder);
  // This stage is under way: its own entry says nothing yet.
  std::erase_if(in.stages, [](const StageTime& s) { return s.stage == "report"; });
  const InspectionFiles files = InspectionFilesIn(ws);
  if (NotDone(workspace, "inspect")) {
    // Observations of an earlier model (or of an interrupted inspection) would be shown as
    // this model's.
    in.notes.push_back(
        "Observations and profile left out: workspace.json records the inspect stage as not "
        "done (failed, interrupted, or its model redone since); run `sewer3d inspect`.");
  } else {
    CheckStageFile(workspace, "inspect", files.profile_csv);
    CheckStageFile(workspace, "inspect", files.observations_json);
    if (std::filesystem::exists(files.profile_csv)) in.profile = ReadProfileCsv(files.profile_csv);
    if (std::filesystem::exists(files.observations_json))
      in.observations = ReadObservationsJson(files.observations_json);
    if (in.observations)
      CheckObservationStations(*in.observations, ws / "model" / "model.json",
                               files.observations_json);
  }
  if (NotDone(workspace, "model")) {
    in.notes.push_back(
        "workspace.json records the model stage as not done (failed, interrupted, or its "
        "registration redone since): the maps shown, if any, are an earlier model's.");
  }
  ReportStageReport r;
  for (const char* stage : {"model", "inspect"}) {
    if (const std::string changed = workspace.ChangedOutput(stage); !changed.empty()) {
      r.warnings.push_back(changed + ": not the file the " + stage +
                           " stage wrote in this workspace (edited, or copied from another "
                           "workspace); shown as it is now");
      in.notes.push_back(r.warnings.back());
    }
  }
  for (const EvaluationText& e : in.evaluations) {
    const nlohmann::json j = nlohmann::json::parse(e.json, nullptr, false);
    if (!j.is_discarded() && j.is_object()) continue;
    r.warnings.push_back((ws / "evaluation" / e.name / "evaluation.json").string() +
                         ": not a JSON object (damaged or cut short); its accuracy figures are "
                         "left out of the report");
  }
  r.html = workspace.StageFolder("report") / "index.html";
  r.summary = WriteReport(in, r.html);
  r.observations = in.observations ? static_cast<int>(in.observations->size()) : -1;
  r.profile_rows = in.profile ? static_cast<int>(in.profile->rows.size()) : -1;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  workspace.FinishStage("report", true,
                        {{"maps", r.summary.maps ? "yes" : "no"},
                         {"viewer", r.summary.viewer ? "yes" : "no"},
                         {"bytes", std::to_string(r.summary.html_bytes)}});
  return r;
}

}  // namespace sewer3d
