#include "sewer3d/simio/simulate_run.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <mutex>

#include "sewer3d/core/check.hpp"
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
  info.created_by = "sewer3d simulate run";
  info.scenario = s.name;
  info.seed = s.seed;
  info.acquisition_period_s = plan.period_s;
  info.color_filter = ColorFilterName(s.render.sensor.color_filter);
  WriteRunInfo(out / "run.json", info,
               {s.rig.modules, plan.acquisitions, static_cast<int>(plan.shots.size()), seconds});
}

}  // namespace

SimulatedRun SimulateRun(const Scenario& scenario, const ModuleDescription& module_in,
                         const BinaryArray& pattern, const fs::path& out,
                         const RunProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  scenario.Check();
  ModuleDescription module = module_in;
  module.pattern.matrix_path = "pattern.png";
  // Errors in the scenario file's terms: "rig.stagger_mm", "capture.nominal_diameter_mm".
  Rig rig;
  CheckWithin("rig.", [&] { rig = MakeRig(module, scenario.rig); });
  const PipeGeometry pipe(scenario.world);
  const Trajectory trajectory(pipe, scenario.motion, scenario.seed);
  SimulatedRun result;
  CheckWithin("capture.", [&] { result.plan = PlanCaptures(rig, trajectory, scenario.capture); });
  result.duration_s = trajectory.DurationS();
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
  std::atomic<int> done{0};
  std::mutex progress_mutex;
  tbb::parallel_for(0, total, 1, [&](int i) {
    const RunImage& shot = plan.shots[i];
    const RigModule& m = rig.modules[shot.module];
    const Rigid3d world_from_camera = poses[i].world_from_carrier * m.carrier_from_camera;
    RenderOptions o = scenario.render;
    o.images = shot.kind == ImageKind::kPattern ? RenderImages::kPattern : RenderImages::kTexture;
    o.seed = static_cast<std::uint64_t>(
        HashUniform(scenario.seed, shot.module, shot.counter, static_cast<int>(shot.kind)) *
        0x1p53);
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
    const bool truth =
        scenario.truth_depth == TruthDepth::kAll ||
        (scenario.truth_depth == TruthDepth::kPattern && shot.kind == ImageKind::kPattern);
    o.truth_depth = truth;
    o.white_balance = white_balance[shot.module];
    // Pattern images too: the colour the RGB-D stage gives at the pattern instant is judged
    // against what the camera saw then.
    o.truth_albedo = scenario.truth_albedo;
    const RenderedFrame frame =
        RenderFrame(m.module, pattern, PipeView(pipe, world_from_camera), o);
    const fs::path image = out / index[i].file;
    if (shot.kind == ImageKind::kPattern)
      WritePatternImage(image, frame, o.sensor.bits);
    else
      WriteTextureImage(image, frame, o.sensor.bits);
    if (truth) {
      WriteImage(
          out / "truth" / "depth" / (ImageStem(shot.module, shot.counter, shot.kind) + ".tiff"),
          frame.truth_depth);
    }
    if (o.truth_albedo) {
      WriteTruthAlbedo(out / "truth" / "albedo" / ImageStem(shot.module, shot.counter, shot.kind),
                       frame.truth_albedo);
    }
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
