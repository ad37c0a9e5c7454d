#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/inspection_io.hpp"
#include "sewer3d/io/json_reader.hpp"
#include "sewer3d/io/model_io.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/simeval/inspection_evaluation.hpp"
#include "sewer3d/simeval/truth_alignment.hpp"
#include "sewer3d/simio/scenario_io.hpp"

namespace sewer3d {

InspectionFilesEvaluation EvaluateInspection(const std::filesystem::path& run_folder,
                                             const std::filesystem::path& workspace,
                                             double local_alignment_mm) {
  const InspectionFiles files = InspectionFilesIn(workspace);
  if (!std::filesystem::exists(files.observations_json))
    throw FileError(files.observations_json, "missing: run `sewer3d inspect` first");
  const CaptureRun run = LoadRun(run_folder);
  const TruthAlignment alignment = AlignRegistrationToTruth(run, run_folder, workspace);
  const PipeGeometry truth(ReadScenario(run_folder / "truth" / "scenario.json").world);
  const PipeModelInfo info = ReadModelJson(workspace / "model" / "model.json");

  const std::filesystem::path report = files.folder / "report.json";
  const JsonReader reader(report);
  const nlohmann::json r = reader.ParseObject(ReadTextFile(report));
  InspectionEvaluationOptions options;
  // null: no ring of the pipe was inspected (inspect writes NaN so), nothing is in range.
  const auto station = [&](const char* key) {
    const auto it = r.find(key);
    return it != r.end() && it->is_null() ? std::numeric_limits<double>::quiet_NaN()
                                          : reader.Number(r, key, "");
  };
  options.inspected_from_mm = station("inspected_from_mm");
  options.inspected_to_mm = station("inspected_to_mm");
  if (local_alignment_mm > 0.0) {
    options.truth_from_model_near = [&](double station_mm) {
      return LocalTruthFromModel(alignment, info.centreline, station_mm, local_alignment_mm);
    };
  }

  InspectionFilesEvaluation e;
  e.observations = EvaluateObservations(ReadObservationsJson(files.observations_json), truth,
                                        alignment.truth_from_model, info.centreline, options);
  e.profile = EvaluateProfileAgainstTruth(ReadProfileCsv(files.profile_csv), info.centreline, truth,
                                          alignment.truth_from_model, ProfileOptions{},
                                          ProfileEvaluationOptions{});
  return e;
}

std::string InspectionEvaluationToJson(const InspectionFilesEvaluation& e) {
  const auto number = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nullptr; };
  nlohmann::json items = nlohmann::json::array();
  for (const TrueItemMatch& m : e.observations.items) {
    nlohmann::json values = nlohmann::json::array();
    for (const TrueItemMatch::Value& v : m.values) {
      values.push_back({{"name", v.name}, {"truth", v.truth}, {"measured", number(v.measured)}});
    }
    items.push_back({{"truth_id", m.truth_id},
                     {"code", m.code},
                     {"station_mm", m.station_mm},
                     {"clock_h", m.clock_h},
                     {"inspected", m.inspected},
                     {"observation_id", m.observation_id},
                     {"station_error_mm", m.station_error_mm},
                     {"clock_error_h", m.clock_error_h},
                     {"values", values}});
  }
  return nlohmann::json{{"observations",
                         {{"inspected", e.observations.inspected},
                          {"found", e.observations.found},
                          {"invented", e.observations.invented},
                          {"items", items}}},
                        {"profile", nlohmann::json::parse(ProfileEvaluationToJson(e.profile))}}
             .dump(1) +
         "\n";
}

}  // namespace sewer3d
