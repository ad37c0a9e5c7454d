#include "sewer3d/pipeline/model_stage.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/model_io.hpp"
#include "sewer3d/io/pose_checks.hpp"
#include "sewer3d/io/registration_io.hpp"
#include "sewer3d/io/rgbd_io.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/model/unroll.hpp"
#include "sewer3d/pipeline/model_outputs.hpp"
#include "sewer3d/pipeline/model_samples.hpp"
#include "sewer3d/pipeline/parallel_items.hpp"
#include "sewer3d/texture/shading.hpp"

namespace sewer3d {
namespace {

using Clock = std::chrono::steady_clock;
constexpr const char* kStage = "model";

/// How many acquisitions the registration registered (registration/report.json "nodes"); 0
/// when the report cannot be read.
int RegisteredNodes(const std::filesystem::path& ws) {
  try {
    return nlohmann::json::parse(ReadTextFile(ws / "registration" / "report.json"))
        .at("nodes")
        .get<int>();
  } catch (const std::exception&) {
    return 0;
  }
}

/// Refuses poses.csv left by an earlier registration: workspace.json records the register stage
/// as not done (stale after rgbd redid acquisitions or the run's files changed, failed or
/// interrupted).
void CheckRegistrationDone(const Workspace& workspace) {
  const auto it = workspace.record().stages.find("register");
  const std::filesystem::path poses = workspace.StageFolder("registration") / "poses.csv";
  if (it == workspace.record().stages.end() || it->second.done || !IsRegularFile(poses)) return;
  throw FileError(poses, std::string("left by an earlier registration: workspace.json records the "
                                     "register stage as ") +
                             (it->second.stale ? "stale (rgbd or the run's files changed since)"
                                               : "not done (failed or interrupted)") +
                             ": run `sewer3d register` first, or `sewer3d process`");
}

/// The registered acquisitions, each with its fit samples (model frame).
std::vector<ModelAcquisition> RegisteredAcquisitions(
    const CaptureRun& run, const std::filesystem::path& ws, int samples_per_acquisition,
    int threads, std::vector<std::vector<Eigen::Vector3d>>& samples,
    const ModelProgress& progress) {
  const std::filesystem::path poses_file = ws / "registration" / "poses.csv";
  if (!std::filesystem::exists(poses_file))
    throw FileError(poses_file, "missing: run the register stage first");
  std::vector<ModelAcquisition> acquisitions;
  const std::vector<RegistrationPoseRow> rows = ReadRegistrationPoses(poses_file);
  for (const std::string& problem : {PoseJumpProblem(rows), PoseTravelProblem(rows, run.odometry),
                                     PoseDirectionProblem(rows, run.odometry, run.rig),
                                     PoseRigProblem(rows, run.odometry, run.rig)}) {
    if (!problem.empty()) throw FileError(poses_file, problem);
  }
  for (const RegistrationPoseRow& row : rows) {
    if (row.module < 0 || row.module >= static_cast<int>(run.rig.modules.size()))
      throw FileError(poses_file, "module " + std::to_string(row.module) + " is not in the rig");
    acquisitions.push_back({row.module, row.counter, row.world_from_camera});
  }
  if (acquisitions.empty()) throw FileError(poses_file, "no registered acquisition");
  if (const int nodes = RegisteredNodes(ws);
      nodes > static_cast<int>(acquisitions.size())) {  // rows removed by hand
    throw FileError(poses_file, fmt::format("holds {} poses, but the registration registered {} "
                                            "(registration/report.json): run register again",
                                            acquisitions.size(), nodes));
  }
  samples.assign(acquisitions.size(), {});
  ForEachItem<int>(
      acquisitions.size(), threads, [] { return 0; },
      [&](std::size_t i, int&) {
        const ModelAcquisition& a = acquisitions[i];
        const RgbdPairInput in = ReadRgbdForRegistration(ws / "rgbd", a.module, a.counter);
        const CameraModel camera(run.rig.modules[a.module].module.camera);
        samples[i] = FitSamples(in.depth_mm, camera, a.world_from_camera, samples_per_acquisition);
      },
      [&](int finished) {
        if (progress) progress("samples", finished, static_cast<int>(acquisitions.size()));
      });
  return acquisitions;
}

/// Each acquisition's station span from its samples; the grid over all of them.
MapGrid StationGrid(const Centreline& centreline,
                    const std::vector<std::vector<Eigen::Vector3d>>& samples,
                    std::vector<ModelAcquisition>& acquisitions, double resolution_mm) {
  double begin = std::numeric_limits<double>::infinity(), end = -begin;
  for (std::size_t i = 0; i < acquisitions.size(); ++i) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo, guess = 0.0;
    for (const Eigen::Vector3d& p : samples[i]) {
      guess = Unroll(centreline, p, guess).station_mm;
      lo = std::min(lo, guess);
      hi = std::max(hi, guess);
    }
    acquisitions[i].station_min_mm = lo;
    acquisitions[i].station_max_mm = hi;
    if (lo <= hi) begin = std::min(begin, lo), end = std::max(end, hi);
  }
  begin = std::floor(begin / resolution_mm) * resolution_mm;
  return MakeMapGrid(begin, end, centreline.radius_mm, resolution_mm);
}

double SplatRadius(const CaptureRun& run, const ModelStageOptions& o) {
  if (o.maps.splat_radius_mm > 0.0) return o.maps.splat_radius_mm;
  double footprint = 0.0;
  for (const RigModule& m : run.rig.modules)
    footprint = std::max(footprint, o.depth_ref_mm / m.module.camera.fx * o.pixel_step);
  return footprint > 0.7 * o.resolution_mm ? footprint : 0.0;
}

double NominalDiameter(const ModelStageOptions& options, double fitted_radius_mm) {
  if (options.nominal_diameter_mm > 0.0) return options.nominal_diameter_mm;
  return 5.0 * std::round(2.0 * fitted_radius_mm / 5.0);
}

/// Accumulates and writes every tile not written by an earlier run.
void WriteTiles(const CaptureRun& run, const std::filesystem::path& ws, const Centreline& line,
                const std::vector<ModelAcquisition>& acquisitions, const ModelStageOptions& o,
                PipeModelInfo& info, ModelStageReport& report, const ModelProgress& progress) {
  const std::filesystem::path folder = ws / kStage;
  // At most kMaxTileCells per tile whatever the resolution: memory stays bounded.
  constexpr double kMaxTileCells = 8e6;
  const int tile_rows = std::max(
      1, static_cast<int>(std::min(std::round(o.tile_length_mm / o.resolution_mm),
                                   std::floor(kMaxTileCells / std::max(info.grid.cols, 1)))));
  for (int row0 = 0, k = 0; row0 < info.grid.rows; row0 += tile_rows, ++k)
    info.tiles.push_back({k, row0, std::min(tile_rows, info.grid.rows - row0)});
  report.tiles = static_cast<int>(info.tiles.size());
  std::vector<cv::Mat2f> normalised;  // per module, shared by every tile
  for (const RigModule& m : run.rig.modules)
    normalised.push_back(NormalisedCoordinates(CameraModel(m.module.camera)));
  for (const ModelTile& tile : info.tiles)
    report.tiles_from_earlier_run += ModelTileDone(folder, tile.index) ? 1 : 0;
  ForEachItem<int>(
      info.tiles.size(), o.threads, [] { return 0; },
      [&](std::size_t t, int&) {
        const ModelTile& tile = info.tiles[t];
        if (ModelTileDone(folder, tile.index)) return;
        const MapGrid grid = info.grid.Tile(tile.row0, tile.rows);
        const double lo = grid.station0_mm, hi = lo + grid.rows * grid.resolution_mm;
        MapAccumulatorOptions map_options = o.maps;
        map_options.splat_radius_mm = report.splat_radius_mm;
        MapAccumulator maps(line, grid, map_options);
        for (const ModelAcquisition& a : acquisitions) {
          if (a.station_max_mm < lo - 5.0 || a.station_min_mm > hi + 5.0) continue;
          const RgbdPairInput in = ReadRgbdForRegistration(ws / "rgbd", a.module, a.counter);
          if (in.depth_mm.size() != normalised[a.module].size())
            throw FileError(RgbdAcquisitionFiles(ws / "rgbd", a.module, a.counter).depth,
                            "not the size of module " + std::to_string(a.module) + "'s camera");
          const PixelWeighting weighting{o.pixel_step, o.feather_fraction * in.depth_mm.cols,
                                         o.depth_sigma_ref_mm, o.depth_ref_mm,
                                         report.module_offsets.range_mm[a.module]};
          AddAcquisitionPixels(maps, in.depth_mm, in.color_bgr, normalised[a.module],
                               a.world_from_camera, weighting);
        }
        WriteModelTile(folder, tile.index, maps.Finish(), info.grid, line, o.files);
      },
      [&](int finished) {
        if (progress) progress("tiles", finished, report.tiles);
      });
}

// The register stage's odometry warnings (registration/report.json), which explain most
// centrelines that cannot be fitted: a jump or gap in the odometry scatters the acquisitions
// it places. Empty when there are none.
std::string OdometryHint(const std::filesystem::path& ws) {
  try {
    const nlohmann::json j =
        nlohmann::json::parse(ReadTextFile(ws / "registration" / "report.json"));
    const nlohmann::json& warnings = j.at("initial_poses").at("odometry_warnings");
    if (!warnings.is_array() || warnings.empty()) return {};
    return fmt::format("; the registration warned of the odometry ({} warning{}), first: {}",
                       warnings.size(), warnings.size() == 1 ? "" : "s",
                       warnings.front().get<std::string>());
  } catch (const std::exception&) {
    return {};  // an old or damaged report: the message goes without the hint
  }
}

}  // namespace

void ModelStageOptions::Check() const {
  ValidatePositive("resolution_mm", resolution_mm);
  SEWER3D_VALIDATE(resolution_mm >= 0.01 && resolution_mm <= 50.0, "resolution_mm",
                   "must lie in [0.01, 50] mm, got " << resolution_mm);
  SEWER3D_VALIDATE(std::isfinite(start_station_mm), "start_station_mm", "must be finite");
  ValidateNotNegative("nominal_diameter_mm", nominal_diameter_mm);
  ValidatePositive("tile_length_mm", tile_length_mm);
  SEWER3D_VALIDATE(fit_samples_per_acquisition >= 10, "fit_samples_per_acquisition",
                   "must be at least 10");
  SEWER3D_VALIDATE(pixel_step >= 1, "pixel_step", "must be at least 1");
  SEWER3D_VALIDATE(feather_fraction > 0.0 && feather_fraction <= 0.5, "feather_fraction",
                   "must lie in (0, 0.5]");
  ValidatePositive("depth_sigma_ref_mm", depth_sigma_ref_mm);
  ValidatePositive("depth_ref_mm", depth_ref_mm);
  centreline.Check();
  maps.Check();
  offsets.Check();
  files.Check();
  base.Check();
  displaced.Check();
  SEWER3D_VALIDATE(threads >= 1, "threads", "must be at least 1, got " << threads);
}

ModelStageReport RunModelStage(const CaptureRun& run, Workspace& workspace,
                               const ModelStageOptions& options, const ModelProgress& progress) {
  options.Check();
  const auto start = Clock::now();
  // The model begins (with --force: the earlier one removed) once the fit has accepted the
  // options: a refused --nominal-diameter-mm leaves the earlier model as it was.
  workspace.CheckBeginStage(kStage, ModelOptionsJson(options), options.force);
  const auto begin = [&] {
    workspace.BeginStage(kStage, ModelOptionsJson(options), options.force);
    if (options.force) RemoveFolder(workspace.StageFolder(kStage));
  };
  const std::filesystem::path ws = workspace.folder(), folder = workspace.StageFolder(kStage);
  ModelStageReport report;
  report.threads = options.threads;

  CheckRegistrationDone(workspace);
  if (const std::string changed = workspace.ChangedOutput("register"); !changed.empty()) {
    report.warnings.push_back(changed +
                              ": not the file the register stage wrote (edited, or copied from "
                              "another workspace); the model follows it as it is now");
  }
  std::vector<std::vector<Eigen::Vector3d>> samples;
  std::vector<ModelAcquisition> acquisitions = RegisteredAcquisitions(
      run, ws, options.fit_samples_per_acquisition, options.threads, samples, progress);
  report.acquisitions = static_cast<int>(acquisitions.size());
  std::vector<Eigen::Vector3d> all;
  for (const auto& s : samples) all.insert(all.end(), s.begin(), s.end());
  report.fit_points = static_cast<int>(all.size());

  CentrelineFitOptions fit_options = options.centreline;
  fit_options.straight = options.straight;
  fit_options.start_station_mm = options.start_station_mm;
  CentrelineFit fit = FitCentreline(all, fit_options);
  report.centreline = fit.report;
  if (!fit.converged) {
    // Usually too little of the circumference measured (acquisitions left out, few modules).
    report.message = fmt::format(
        "no centreline: {} of {} cross-section slices usable in {} points from {} acquisitions "
        "(a slice needs {} points over {:.0f} deg of the wall): too little of the pipe measured",
        fit.report.slices_used, fit.report.slices_used + fit.report.slices_rejected, all.size(),
        acquisitions.size(), fit_options.min_slice_points, fit_options.min_slice_coverage_deg);
    report.message += OdometryHint(ws);
    begin();
    workspace.FinishStage(kStage, false, {{"error", report.message}});
    return report;
  }
  report.nominal_diameter_mm = NominalDiameter(options, fit.report.radius_mm);
  // The displacement is measured from the nominal wall; a nominal far from the measured pipe
  // is a wrong option, not a model (a real pipe is within a few % of its DN).
  const double fitted_mm = 2.0 * fit.report.radius_mm;
  SEWER3D_VALIDATE(std::abs(report.nominal_diameter_mm - fitted_mm) <= 0.25 * fitted_mm,
                   "nominal_diameter_mm",
                   "must be within 25 % of the measured diameter (" << fitted_mm << " mm), got "
                                                                    << report.nominal_diameter_mm);
  fit.centreline.radius_mm = 0.5 * report.nominal_diameter_mm;
  begin();

  PipeModelInfo info;
  info.centreline = fit.centreline;
  info.start_station_mm = options.start_station_mm;
  info.encoding = options.files.encoding;
  info.view_range_mm = options.files.view_range_mm;
  info.grid = StationGrid(info.centreline, samples, acquisitions, options.resolution_mm);
  report.module_offsets.range_mm.assign(run.rig.modules.size(), 0.0);
  report.module_offsets.why = "off (--no-module-offsets)";
  if (options.module_offsets) {
    ModuleOffsetEstimator estimator(static_cast<int>(run.rig.modules.size()),
                                    info.centreline.radius_mm, options.offsets);
    AddWallSamples(estimator, info.centreline, acquisitions, samples);
    report.module_offsets = estimator.Estimate();
  }
  samples.clear();
  report.grid = info.grid;
  report.splat_radius_mm = SplatRadius(run, options);
  // Beyond a few millimetres the maps hold splats, not the wall's detail (joints, cracks).
  constexpr double kCoarseSplatMm = 2.0;
  if (report.splat_radius_mm > kCoarseSplatMm) {
    report.warnings.push_back(fmt::format(
        "a pixel step of {} (--pixel-step) samples the wall every {:.1f} mm: the {:g} mm maps hold "
        "{:.1f} mm splats, "
        "not the wall's detail (joint gaps, cracks); a step of 1 to 4 keeps it",
        options.pixel_step, report.splat_radius_mm, options.resolution_mm, report.splat_radius_mm));
  }
  WriteTiles(run, ws, info.centreline, acquisitions, options, info, report, progress);

  const MapFilesReport files = FinishTiledModel(folder, info, options.files);
  report.surface_points = files.surface_points;
  WriteModelMeshes(folder, info, options, report, progress);
  if (report.whole_maps && !options.keep_tiles) {
    // The tiles duplicate the whole-run files now: model.json without them first, so the
    // folder is a complete model at every moment.
    info.tiles.clear();
    info.whole_maps = true;
    WriteModelJson(folder / "model.json", info);
    RemoveFolder(folder / "tiles");
  }
  report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  report.seconds_per_acquisition = report.seconds / report.acquisitions;
  report.ok = true;
  WriteModelReport(folder, report);
  workspace.FinishStage(kStage, true,
                        {{"acquisitions", std::to_string(report.acquisitions)},
                         {"rows", std::to_string(info.grid.rows)},
                         {"cols", std::to_string(info.grid.cols)},
                         {"tiles", std::to_string(report.tiles)}});
  return report;
}

bool ModelFilesPresent(const std::filesystem::path& model_dir) {
  PipeModelInfo info;
  try {
    info = ReadModelJson(model_dir / "model.json");
  } catch (const FileError&) {
    return false;
  }
  std::vector<ModelMapFiles> maps;
  if (info.whole_maps) maps.push_back(WholeMapFiles(model_dir));
  for (const ModelTile& t : info.tiles) maps.push_back(TileMapFiles(model_dir, t.index));
  std::vector<std::filesystem::path> files = {model_dir / "mesh.obj", model_dir / "mesh.mtl",
                                              model_dir / "preview.png", model_dir / "report.json"};
  if (!info.whole_maps) files.push_back(model_dir / "mesh_texture.png");
  for (const ModelMapFiles& m : maps) {
    files.insert(files.end(), {m.texture, m.displacement_png, m.displacement_tiff, m.coverage,
                               m.samples, m.displacement_view, m.surface});
  }
  return std::all_of(files.begin(), files.end(),
                     [](const std::filesystem::path& f) { return IsRegularFile(f); });
}

}  // namespace sewer3d
