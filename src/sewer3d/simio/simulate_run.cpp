#include "sewer3d/simio/simulate_run.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>

#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/sim/material.hpp"
#include "sewer3d/sim/odometry.hpp"
#include "sewer3d/sim/surface.hpp"
#include "sewer3d/simio/run_overview.hpp"
#include "sewer3d/simio/scenario_io.hpp"
#include "sewer3d/simio/scene_io.hpp"
#include "sewer3d/simio/simulate_inclinometer.hpp"
#include "sewer3d/simio/truth_io.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

std::uintmax_t FolderBytes(const fs::path& dir) {
  std::uintmax_t bytes = 0;
  std::error_code ec;
  for (const auto& e : fs::recursive_directory_iterator(dir, ec)) {
    if (e.is_regular_file(ec)) bytes += e.file_size(ec);
  }
  return bytes;
}

void WriteRunJson(const fs::path& out, const Scenario& s, const CapturePlan& plan, bool complete,
                  double seconds) {
  RunInfo info;
  info.complete = complete;
  info.created_by = kSimulatedRunCreator;
  info.scenario = s.name;
  info.seed = s.seed;
  info.acquisition_period_s = plan.period_s;
  info.color_filter = ColorFilterName(s.render.sensor.color_filter);
  WriteRunInfo(out / "run.json", info,
               {s.rig.modules, plan.acquisitions, static_cast<int>(plan.shots.size()), seconds});
}

// The rig, pipe, trajectory and capture plan of a scenario; errors in the scenario file's
// terms ("rig.stagger_mm", "capture.nominal_diameter_mm").
struct RunSetup {
  RunSetup(const Scenario& scenario, const ModuleDescription& module)
      : rig(CheckedRig(scenario, module)),
        pipe(scenario.world),
        trajectory(pipe, scenario.motion, scenario.seed) {
    CheckWithin("capture.", [&] { plan = PlanCaptures(rig, trajectory, scenario.capture); });
  }
  static Rig CheckedRig(const Scenario& scenario, const ModuleDescription& module) {
    scenario.Check();
    Rig rig;
    CheckWithin("rig.", [&] { rig = MakeRig(module, scenario.rig); });
    return rig;
  }
  Rig rig;
  PipeGeometry pipe;
  Trajectory trajectory;
  CapturePlan plan;
};

// An earlier run in `out` loses its images and truth (a shorter run must not leave stale images
// behind); a folder with anything else in it is not ours to fill.
void PrepareRunFolder(const fs::path& out) {
  std::error_code ec;
  if (!fs::exists(out, ec)) return;
  if (!fs::is_directory(out, ec)) throw FileError(out, "exists and is not a folder");
  if (fs::is_empty(out, ec)) return;
  if (!fs::is_regular_file(out / "run.json", ec))
    throw FileError(out, "the folder is not empty and holds no run; choose a new or empty folder");
  // Only a simulated run is replaced: a real capture's images cannot be made again.
  if (!IsSimulatedRun(out)) {
    throw FileError(out,
                    "holds a capture run the simulator did not make (run.json created_by); "
                    "choose a new or empty folder");
  }
  for (const char* sub : {"images", "truth"}) RemoveFolder(out / sub);
}

// Whether `out` holds an interrupted simulation of this very run (same scenario, rig and
// pattern): the images it finished are the ones this simulation would render.
bool IsInterruptedRunOf(const fs::path& out, const Scenario& s, const Rig& rig,
                        const BinaryArray& pattern) {
  try {
    return IsSimulatedRun(out) && !ReadRunInfo(out / "run.json").complete &&
           ReadTextFile(out / "truth" / "scenario.json") == ScenarioToJson(s) + "\n" &&
           ReadTextFile(out / "rig.json") == RigToJson(rig) &&
           ReadPatternMatrix(out / "pattern.png") == pattern;
  } catch (const std::exception&) {
    return false;  // anything unreadable: not a run to resume
  }
}

bool WritesTruthDepth(const Scenario& s, const RunImage& shot) {
  return s.truth_depth == TruthDepth::kAll ||
         (s.truth_depth == TruthDepth::kPattern && shot.kind == ImageKind::kPattern);
}

// The files one shot writes: its image, and its truth depth and albedo where the scenario asks.
struct ShotFiles {
  ShotFiles(const fs::path& out, const Scenario& s, const RunImage& shot) : image(out / shot.file) {
    const std::string stem = ImageStem(shot.module, shot.counter, shot.kind);
    if (WritesTruthDepth(s, shot)) depth = out / "truth" / "depth" / (stem + ".tiff");
    if (s.truth_albedo) albedo_stem = out / "truth" / "albedo" / stem;
  }
  // All of them on disk (each written atomically: a file there is whole).
  bool Written() const {
    std::vector<fs::path> files{image};
    if (!depth.empty()) files.push_back(depth);
    if (!albedo_stem.empty()) {
      for (const fs::path& f : TruthAlbedoFiles(albedo_stem)) files.push_back(f);
    }
    return std::all_of(files.begin(), files.end(),
                       [](const fs::path& f) { return IsRegularFile(f); });
  }
  fs::path image, depth, albedo_stem;  // empty: not written
};

}  // namespace

bool IsSimulatedRun(const fs::path& folder) {
  try {
    return ReadRunInfo(folder / "run.json").created_by == kSimulatedRunCreator &&
           fs::is_directory(folder / "truth");
  } catch (const FileError&) {
    return false;
  }
}

RunSizeEstimate EstimateRunSize(const Scenario& scenario, const ModuleDescription& module) {
  const RunSetup setup(scenario, module);
  RunSizeEstimate size;
  size.images = static_cast<int>(setup.plan.shots.size());
  size.duration_s = setup.trajectory.DurationS();
  size.odometry_rows = static_cast<std::uint64_t>(size.duration_s * scenario.odometry.rate_hz) + 1;
  // Bytes per pixel measured on simulated runs: a pattern or raw texture PNG about 0.15 (0.5
  // allowed), a truth depth TIFF 4 (float), a truth albedo PNG about 1.5 (2 allowed).
  const double pixels = double(module.camera.width) * module.camera.height;
  int depth_maps = 0;
  for (const RunImage& shot : setup.plan.shots) {
    depth_maps += WritesTruthDepth(scenario, shot);
  }
  const double per_image = 0.5 + (scenario.truth_albedo ? 2.0 : 0.0);
  size.bytes = static_cast<std::uintmax_t>(pixels * (per_image * size.images + 4.0 * depth_maps));
  return size;
}

void CheckRunFits(const RunSizeEstimate& size, const fs::path& out) {
  SEWER3D_VALIDATE(size.images <= kMaxPlannedImages, "",
                   "the run would take " << size.images << " images, more than the "
                                         << kMaxPlannedImages << " allowed");
  SEWER3D_VALIDATE(size.odometry_rows <= kMaxOdometryRows, "",
                   "the run would last " << size.duration_s << " s, " << size.odometry_rows
                                         << " odometry rows, more than the " << kMaxOdometryRows
                                         << " allowed");
  // The nearest existing folder above `out` tells the file system.
  fs::path probe = fs::absolute(out);
  std::error_code ec;
  while (!fs::exists(probe, ec) && probe.has_parent_path() && probe != probe.parent_path())
    probe = probe.parent_path();
  const fs::space_info space = fs::space(probe, ec);
  SEWER3D_VALIDATE(ec || size.bytes <= space.available, "",
                   "the run would take about "
                       << size.bytes / 1e9 << " GB with its truth, more than the "
                       << space.available / 1e9 << " GB free under " << probe.string());
}

SimulatedRun SimulateRun(const Scenario& scenario, const ModuleDescription& module_in,
                         const BinaryArray& pattern, const fs::path& out,
                         const RunProgress& progress, bool restart) {
  const auto start = std::chrono::steady_clock::now();
  ModuleDescription module = module_in;
  module.pattern.matrix_path = "pattern.png";
  const RunSetup setup(scenario, module);
  const Rig& rig = setup.rig;
  const PipeGeometry& pipe = setup.pipe;
  const Trajectory& trajectory = setup.trajectory;
  SimulatedRun result;
  result.plan = setup.plan;
  result.duration_s = trajectory.DurationS();
  const bool resume = !restart && IsInterruptedRunOf(out, scenario, rig, pattern);
  if (!resume) PrepareRunFolder(out);
  result.overlap =
      NeighbourOverlaps(rig, scenario.capture.nominal_diameter_mm, Eigen::Vector2d::Zero(), true);
  const CapturePlan& plan = result.plan;

  // Everything but the images first: a run that stops part-way still says what it holds.
  std::error_code ec;
  fs::create_directories(out / "truth", ec);
  if (ec) throw FileError(out, "cannot create folder: " + ec.message());
  WriteRunJson(out, scenario, plan, false, 0.0);
  WriteRig(out / "rig.json", rig);
  WritePatternMatrix(out / "pattern.png", pattern);
  const std::vector<RunImage>& index = plan.shots;
  std::vector<TruthPose> poses;
  for (const RunImage& s : plan.shots) {
    poses.push_back({s.module, s.counter, s.kind, s.time_s, trajectory.StationAt(s.time_s),
                     trajectory.WorldFromCarrier(s.time_s)});
  }
  WriteIndex(out / "acquisitions.csv", index);
  const auto odometry = SimulateOdometry(trajectory, scenario.odometry, scenario.seed);
  std::vector<OdometryReading> readings;
  for (const OdometrySample& o : odometry) readings.push_back({o.time_s, o.measured_mm});
  WriteOdometry(out / "odometry.csv", readings);
  WriteOdometryTruth(out / "truth" / "odometry.csv", odometry);
  WriteSimulatedInclinometer(out, scenario, trajectory);
  WriteTruthPoses(out / "truth" / "poses.csv", poses);
  std::vector<Eigen::Vector3d> white_balance;
  for (int k = 0; k < scenario.rig.modules; ++k)
    white_balance.push_back(CameraWhiteBalance(scenario, k));
  WriteCameraGains(out / "truth" / "camera_gains.csv", white_balance);
  WriteTextFile(out / "truth" / "scenario.json", ScenarioToJson(scenario) + "\n");
  WriteTextFile(out / "truth" / "world.json", PipeWorldToJson(scenario.world) + "\n");
  WriteFeatureTruth(out / "truth" / "features.json", pipe);
  WriteImage(out / "truth" / "overview.png", RunOverview(pipe, rig, trajectory, plan));

  const int total = static_cast<int>(plan.shots.size());
  std::vector<char> kept(total, 0);
  if (resume) {
    for (const char* sub : {"images", "truth"}) RemoveStaleTemporaries(out / sub);
    for (int i = 0; i < total; ++i) kept[i] = ShotFiles(out, scenario, plan.shots[i]).Written();
    result.images_kept = static_cast<int>(std::count(kept.begin(), kept.end(), 1));
  }
  std::atomic<int> done{result.images_kept};
  std::mutex progress_mutex;
  if (progress && resume) progress(result.images_kept, total);
  tbb::parallel_for(0, total, 1, [&](int i) {
    if (kept[i]) return;
    const RunImage& shot = plan.shots[i];
    const RigModule& m = rig.modules[shot.module];
    const Rigid3d world_from_camera = poses[i].world_from_carrier * m.carrier_from_camera;
    RenderOptions o = scenario.render;
    o.images = shot.kind == ImageKind::kPattern ? RenderImages::kPattern : RenderImages::kTexture;
    o.seed = static_cast<std::uint64_t>(
        HashUniform(scenario.seed, shot.module, shot.counter, static_cast<int>(shot.kind)) *
        0x1p53);
    // Each module's projector and lenses err in their own way (fixed over the run).
    o.spot_errors.projector_seed =
        scenario.render.spot_errors.projector_seed + 1000003ULL * shot.module;
    // Motion during the exposure, in the camera frame.
    const double dt = 0.5e-3;
    const Eigen::Vector3d velocity =
        ((trajectory.WorldFromCarrier(shot.time_s + dt) * m.carrier_from_camera).translation -
         (trajectory.WorldFromCarrier(shot.time_s - dt) * m.carrier_from_camera).translation) /
        (2.0 * dt);
    o.exposure_ms = scenario.capture.exposure_ms;
    o.speed_mm_s = velocity.norm();
    if (o.speed_mm_s > 0.0)
      o.motion_direction = world_from_camera.rotation.conjugate() * velocity.normalized();
    const ShotFiles files(out, scenario, shot);
    o.truth_depth = !files.depth.empty();
    o.white_balance = white_balance[shot.module];
    // Pattern images too: the colour the RGB-D stage gives at the pattern instant is judged
    // against what the camera saw then.
    o.truth_albedo = scenario.truth_albedo;
    const RenderedFrame frame =
        RenderFrame(m.module, pattern, PipeView(pipe, world_from_camera), o);
    // The image last: a shot whose image is on disk has its truth too (resumption checks all).
    if (o.truth_depth) WriteImage(files.depth, frame.truth_depth);
    if (o.truth_albedo) WriteTruthAlbedo(files.albedo_stem, frame.truth_albedo);
    if (shot.kind == ImageKind::kPattern)
      WritePatternImage(files.image, frame, o.sensor.bits);
    else
      WriteTextureImage(files.image, frame, o.sensor.bits);
    const int now = ++done;
    if (progress) {
      const std::lock_guard<std::mutex> lock(progress_mutex);
      progress(now, total);
    }
  });
  result.images = total;
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  WriteRunJson(out, scenario, plan, true, result.wall_seconds);
  result.bytes = FolderBytes(out);
  return result;
}

}  // namespace sewer3d
