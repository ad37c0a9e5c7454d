#include "sewer3d/pipeline/inspect_stage.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <nlohmann/json.hpp>
#include <optional>

#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/inspection_io.hpp"
#include "sewer3d/io/model_io.hpp"
#include "sewer3d/pipeline/inspection_crops.hpp"

namespace sewer3d {
namespace {

using Clock = std::chrono::steady_clock;
using json = nlohmann::json;
constexpr const char* kStage = "inspect";

/// Today's date (UTC) as YYYY-MM-DD.
std::string TodayUtc() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[16];
  std::strftime(text, sizeof text, "%Y-%m-%d", &utc);
  return text;
}

/// Calls `fn` with each piece of the model's maps: `whole` when the model has whole-run maps
/// (read once by the caller and used for both passes), else tile after tile.
void ForEachPiece(const std::filesystem::path& model_dir, const PipeModelInfo& info,
                  const std::optional<PipeMaps>& whole,
                  const std::function<void(const PipeMaps&)>& fn, const InspectProgress& progress,
                  const std::string& pass) {
  if (whole) {
    fn(*whole);
    if (progress) progress(pass, 1, 1);
    return;
  }
  int done = 0;
  for (const ModelTile& t : info.tiles) {
    fn(ReadMapFiles(TileMapFiles(model_dir, t.index), info.grid.Tile(t.row0, t.rows)));
    if (progress) progress(pass, ++done, static_cast<int>(info.tiles.size()));
  }
}

}  // namespace

void InspectStageOptions::Check() const {
  CheckWithin("inspect.", [&] { inspect.Check(); });
  CheckWithin("profile.", [&] { profile.Check(); });
  SEWER3D_VALIDATE(max_crop_side_px >= 16, "max_crop_side_px",
                   "must be at least 16, got " << max_crop_side_px);
}

std::string InspectOptionsJson(const InspectStageOptions& o) {
  const InspectOptions& i = o.inspect;
  return json{{"cell_mm", i.cell_mm},
              {"nominal_diameter_mm", i.nominal_diameter_mm},
              {"min_deformation_pct", i.min_deformation_pct},
              {"min_gap_depth_mm", i.joints.min_gap_depth_mm},
              {"min_offset_mm", i.joints.min_offset_mm},
              {"intrusion_mm", i.defects.intrusion_mm},
              {"surface_mm", i.defects.surface_mm},
              {"texture_cracks", i.cracks.enabled},
              {"crack_min_length_mm", i.cracks.min_length_mm},
              {"profile_step_mm", o.profile.step_mm}}
      .dump();
}

std::string InspectStageReportToJson(const InspectStageReport& r) {
  const InspectionReport& i = r.inspection;
  return json{
      {"ok", r.ok},
      {"message", r.message},
      {"observations", r.observations},
      {"per_code", r.per_code},
      {"coarse_map", {{"rows", i.coarse_rows}, {"cols", i.coarse_cols}, {"cell_mm", i.cell_mm}}},
      // null where no station was inspected (nothing measured the wall's noise)
      {"residual_sigma_mm",
       std::isfinite(r.inspected_from_mm) ? json(i.residual_sigma_mm) : json(nullptr)},
      {"sections", i.sections},
      {"inspected_from_mm", r.inspected_from_mm},
      {"inspected_to_mm", r.inspected_to_mm},
      {"inspected_share", i.inspected_share},
      {"profile_rows", r.profile_rows},
      {"profile_rows_measured", r.profile_rows_measured},
      {"seconds", r.seconds}}
      .dump(1);
}

InspectStageReport RunInspectStage(const CaptureRun& run, Workspace& workspace,
                                   const InspectStageOptions& options,
                                   const InspectProgress& progress) {
  options.Check();
  const auto start = Clock::now();
  const std::filesystem::path model_dir = workspace.StageFolder("model");
  // A model left by an earlier registration while a newer one was interrupted is stale.
  const auto model = workspace.record().stages.find("model");
  if (model != workspace.record().stages.end() && !model->second.done &&
      IsRegularFile(model_dir / "model.json")) {
    throw FileError(model_dir / "model.json",
                    "left by an earlier model: workspace.json records the model stage as not done "
                    "(failed, interrupted, or its registration redone since): run `sewer3d "
                    "model` first");
  }
  if (const std::string changed = workspace.ChangedOutput("model"); !changed.empty()) {
    throw FileError(changed,
                    "not the file the model stage wrote in this workspace (edited, or copied from "
                    "another workspace): run `sewer3d model` again with --force");
  }
  const PipeModelInfo info = ReadModelJson(model_dir / "model.json");
  const double limit = options.inspect.max_map_cell_mm;
  if (info.grid.resolution_mm > limit * (1.0 + 1e-9)) {
    throw FileError(model_dir / "model.json",
                    fmt::format("maps of {:g} mm cells are too coarse to inspect (at most {:g} mm: "
                                "cracks and joint gaps are a few mm wide); make the model with "
                                "`sewer3d model --resolution-mm {:g}` or finer",
                                info.grid.resolution_mm, limit, limit));
  }
  // Before BeginStage, which (with --force) removes the earlier inspection.
  CheckNominalDiameter(options.inspect, info.centreline.radius_mm);
  CheckMapFileSizes(model_dir, info);
  workspace.BeginStage(kStage, InspectOptionsJson(options), options.force);
  const InspectionFiles files = InspectionFilesIn(workspace.folder());

  const TextureCrackOptions& cracks = options.inspect.cracks;
  CoarseMapBuilder coarse(info.grid, options.inspect.cell_mm,
                          cracks.enabled ? cracks.cell_mm : 0.0);
  Profile profile;
  std::optional<PipeMaps> whole;
  if (info.whole_maps) whole = ReadMapFiles(WholeMapFiles(model_dir), info.grid);
  ForEachPiece(
      model_dir, info, whole,
      [&](const PipeMaps& piece) {
        coarse.Add(piece);
        const Profile part = ComputeProfile(piece, info.centreline.radius_mm, options.profile);
        profile.nominal_diameter_mm = part.nominal_diameter_mm;
        profile.rows.insert(profile.rows.end(), part.rows.begin(), part.rows.end());
      },
      progress, "maps");
  const Inspection inspection = Inspect(coarse.Finish(), info.centreline, options.inspect);

  std::vector<MapCrop> boxes;
  for (const Observation& o : inspection.observations) boxes.push_back(o.crop);
  InspectionCrops crops(boxes, info.grid, info.view_range_mm, options.max_crop_side_px);
  const InspectionCrops::Done write = [&](std::size_t i, const cv::Mat3b& image) {
    WriteImage(files.folder / "crops" / (inspection.observations[i].id + ".png"), image);
  };
  ForEachPiece(
      model_dir, info, whole, [&](const PipeMaps& piece) { crops.Add(piece, write); }, progress,
      "crops");
  crops.Finish(write);
  WriteProfileCsv(files.profile_csv, profile);
  WriteObservationsCsv(files.observations_csv, inspection.observations);
  IsybauHeader header;
  header.object_name = run.folder.filename().string();
  header.creation_date = TodayUtc();
  header.profile_height_mm = header.profile_width_mm = profile.nominal_diameter_mm;
  WriteObservationsIsybau(files.observations_xml, inspection.observations, header);
  // observations.json last: its presence means the stage's files are complete.
  WriteObservationsJson(files.observations_json, inspection.observations);

  InspectStageReport report;
  report.ok = true;
  report.inspection = inspection.report;
  report.observations = static_cast<int>(inspection.observations.size());
  for (const Observation& o : inspection.observations) ++report.per_code[o.code];
  report.profile_rows = static_cast<int>(profile.rows.size());
  for (const ProfileRow& row : profile.rows)
    report.profile_rows_measured += std::isfinite(row.circumference_mm) ? 1 : 0;
  report.inspected_from_mm = inspection.report.inspected_from_mm;
  report.inspected_to_mm = inspection.report.inspected_to_mm;
  report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  WriteTextFileAtomically(files.folder / "report.json", InspectStageReportToJson(report) + "\n");
  workspace.FinishStage(kStage, true,
                        {{"observations", std::to_string(report.observations)},
                         {"profile_rows", std::to_string(report.profile_rows)}});
  return report;
}

}  // namespace sewer3d
