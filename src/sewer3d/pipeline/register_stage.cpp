#include "sewer3d/pipeline/register_stage.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <nlohmann/json.hpp>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/rgbd_io.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/pipeline/register_outputs.hpp"
#include "sewer3d/register/depth_geometry.hpp"

namespace sewer3d {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;
// The stage's name in workspace.json (the command's) and its folder (the contract's).
constexpr const char* kStage = "register";
constexpr const char* kFolder = "registration";

/// The nodes whose RGB-D acquisition is complete with depth; the others go to left_out.
std::vector<AcquisitionNode> UsableNodes(const std::vector<AcquisitionNode>& all,
                                         const std::filesystem::path& rgbd_folder, int min_points,
                                         RegisterStageReport& report) {
  std::vector<AcquisitionNode> usable;
  for (const AcquisitionNode& n : all) {
    const RgbdFiles files = RgbdAcquisitionFiles(rgbd_folder, n.module, n.counter);
    if (!RgbdAcquisitionDone(files)) {
      report.left_out.push_back({n.module, n.counter,
                                 "the rgbd stage did not finish it (no " +
                                     files.report.filename().string() +
                                     "; see WS/rgbd/report.json)"});
      continue;
    }
    const json r = json::parse(ReadTextFile(files.report), nullptr, false);
    if (!r.is_object()) throw FileError(files.report, "not a JSON object");
    const long long points = r.value("points", 0LL);
    if (points < min_points) {
      report.left_out.push_back({n.module, n.counter,
                                 "no depth: " + std::to_string(points) + " points (fewer than " +
                                     std::to_string(min_points) + ")"});
      continue;
    }
    usable.push_back(n);
  }
  return usable;
}

/// The carrier's offset from the pipe axis, from the depth maps of the first counter.
CarrierOffsetEstimate FirstInstantOffset(const std::vector<AcquisitionNode>& nodes,
                                         const CaptureRun& run,
                                         const std::filesystem::path& rgbd_folder,
                                         const RegisterStageOptions& options) {
  int first = nodes.front().counter;
  for (const AcquisitionNode& n : nodes) first = std::min(first, n.counter);
  std::vector<ModuleWallPoints> walls;
  for (const AcquisitionNode& n : nodes) {
    if (n.counter != first) continue;
    const RgbdPairInput in = ReadRgbdForRegistration(rgbd_folder, n.module, n.counter);
    const CameraModel camera(run.rig.modules[n.module].module.camera);
    walls.push_back({n.module, SampleDepthPoints(in.depth_mm, camera, options.wall_step_px)});
  }
  return EstimateCarrierOffset(run.rig, walls, options.carrier_offset);
}

constexpr double kMaxCarrierSpeedMmS = 2000.0;

/// The odometry's problems (CaptureRun::odometry_findings) in words, naming the file, its
/// lines and the acquisitions they concern.
std::vector<std::string> OdometryWarnings(const CaptureRun& run,
                                          const std::vector<AcquisitionNode>& nodes) {
  const std::string file = (run.folder / "odometry.csv").string();
  const OdometryFindings& f = run.odometry_findings;
  std::vector<std::string> lines;
  for (const OdometryReversal& r : f.reversals) {
    lines.push_back(fmt::format(
        "{}: line{} {}: the distance goes back from {:.1f} mm to {:.1f} mm (more than {} mm): "
        "{} reading{} dropped, a cable counter only counts forward",
        file, r.first_line == r.last_line ? "" : "s",
        r.first_line == r.last_line ? std::to_string(r.first_line)
                                    : fmt::format("{}-{}", r.first_line, r.last_line),
        r.before_mm, r.lowest_mm, f.options.reversal_tolerance_mm, r.readings,
        r.readings == 1 ? "" : "s"));
  }
  if (!run.odometry.empty()) {
    const double first = run.odometry.front().time_s, last = run.odometry.back().time_s;
    const auto outside = std::count_if(nodes.begin(), nodes.end(), [&](const AcquisitionNode& n) {
      return n.time_s < first || n.time_s > last;
    });
    if (outside > 0) {
      lines.push_back(fmt::format(
          "{}: the readings cover {:.3f}-{:.3f} s, but {} of {} acquisitions lie outside that "
          "span: they got the nearest reading's distance, so the odometry does not place them",
          file, first, last, outside, nodes.size()));
    }
    const auto [low, high] =
        std::minmax_element(run.odometry.begin(), run.odometry.end(),
                            [](const OdometryReading& a, const OdometryReading& b) {
                              return a.distance_mm < b.distance_mm;
                            });
    // A crawler moves at most a few hundred mm/s; a jump far faster is a counter glitch or a
    // reading in other units, and places the acquisitions around it wrongly.
    for (std::size_t i = 1; i < run.odometry.size(); ++i) {
      const OdometryReading &a = run.odometry[i - 1], &b = run.odometry[i];
      const double speed = (b.distance_mm - a.distance_mm) / (b.time_s - a.time_s);
      if (speed > kMaxCarrierSpeedMmS) {
        lines.push_back(fmt::format(
            "{}: lines {}-{}: the distance jumps {:.1f} mm in {:.3f} s ({:.0f} mm/s, more than a "
            "carrier's {:.0f} mm/s): a counter glitch or other units; acquisitions around it are "
            "placed by it",
            file, a.line, b.line, b.distance_mm - a.distance_mm, b.time_s - a.time_s, speed,
            kMaxCarrierSpeedMmS));
        break;  // the first one: the cause is the same for the others
      }
    }
    if (run.odometry.size() >= 2 && high->distance_mm - low->distance_mm < 1.0) {
      lines.push_back(fmt::format(
          "{}: the distance stays at {:.1f} mm in all {} readings: the carrier did not move or "
          "the counter is stuck, so the odometry separates no acquisitions",
          file, low->distance_mm, run.odometry.size()));
    }
  }
  for (const OdometryGap& g : f.gaps) {
    std::string inside;
    double sigma = 0.0;
    int count = 0;
    for (const AcquisitionNode& n : nodes) {
      if (n.time_s <= g.from_s || n.time_s >= g.to_s) continue;
      if (count++ < 6)
        inside += fmt::format("{}m{} counter {}", inside.empty() ? "" : ", ", n.module, n.counter);
      sigma = std::max(sigma, n.distance_sigma_mm);
    }
    if (count > 6) inside += fmt::format(" and {} more", count - 6);
    lines.push_back(fmt::format(
        "{}: no reading between line {} ({:.3f} s) and line {} ({:.3f} s), {:.2f} s (more than "
        "{} s): {}",
        file, g.from_line, g.from_s, g.to_line, g.to_s, g.to_s - g.from_s, f.options.max_gap_s,
        count == 0 ? std::string("no acquisition in it")
                   : fmt::format("{} acquisition{} placed by interpolation with σ up to {:.1f} mm "
                                 "along the pipe ({})",
                                 count, count == 1 ? "" : "s", sigma, inside)));
  }
  return lines;
}

}  // namespace

void RegisterStageOptions::Check() const {
  neighbours.Check();
  pairs.features.Check();
  pairs.projection.Check();
  priors.Check();
  fusion.Check();
  carrier_offset.Check();
  SEWER3D_VALIDATE(min_depth_points >= 0, "min_depth_points", "must not be negative");
  SEWER3D_VALIDATE(wall_step_px >= 1, "wall_step_px", "must be at least 1");
  ValidatePositive("length_scale_mm", length_scale_mm);
  SEWER3D_VALIDATE(threads >= 1, "threads", "must be at least 1, got " << threads);
}

RegisterStageReport RunRegisterStage(const CaptureRun& run, Workspace& workspace,
                                     const RegisterStageOptions& options,
                                     const RegisterProgress& progress) {
  options.Check();
  const auto start = Clock::now();
  workspace.BeginStage(kStage, RegisterOptionsJson(options), options.force);
  // BeginStage has cleared WS/registration when forced or stale.
  const std::filesystem::path folder = workspace.StageFolder(kFolder);
  const std::filesystem::path rgbd_folder = workspace.StageFolder("rgbd");

  RegisterStageReport report;
  report.threads = options.threads;
  const InitialPosesResult initial = InitialPoses(run);
  report.initial = initial.report;
  report.acquisitions = static_cast<int>(initial.nodes.size());
  report.odometry_warnings = OdometryWarnings(run, initial.nodes);
  const std::vector<AcquisitionNode> nodes =
      UsableNodes(initial.nodes, rgbd_folder, options.min_depth_points, report);
  report.nodes = static_cast<int>(nodes.size());
  if (nodes.empty()) {  // nothing to register: the outcome says why, nothing is written
    report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    workspace.FinishStage(kStage, false,
                          {{"nodes", "0"}, {"left_out", std::to_string(report.left_out.size())}});
    return report;
  }

  NeighbourOptions neighbours = options.neighbours;
  report.carrier_offset = FirstInstantOffset(nodes, run, rgbd_folder, options);
  if (progress) progress("walls", 1, 1);
  if (report.carrier_offset.valid)
    neighbours.axis_in_model_mm = report.carrier_offset.axis_in_carrier_mm;
  // Without feature and projection registration (`--edges` naming neither) no pair is
  // registered, so none is searched for (they would count as failed).
  NeighbourResult pairs;
  if (options.pairs.feature_registration || options.pairs.projection_fallback)
    pairs = FindNeighbours(nodes, run.rig, neighbours);
  report.neighbours = pairs.report;
  report.pairs = static_cast<int>(pairs.pairs.size());

  const PairRegistrationOutcome outcome =
      RegisterPairs(nodes, pairs.pairs, run.rig, rgbd_folder, folder / "pairs", options.pairs,
                    options.threads, [&](int finished) {
                      if (progress) progress("pairs", finished, report.pairs);
                    });
  report.pairs_done = outcome.done;
  report.pairs_skipped = outcome.skipped;
  if (outcome.done > 0) report.seconds_per_pair = outcome.seconds_now / outcome.done;

  std::vector<RegistrationEdge> edges;
  for (size_t i = 0; i < pairs.pairs.size(); ++i) {
    const PairRecord& r = outcome.records[i];
    if (const std::optional<RegistrationEdge> e = PairEdge(r, pairs.pairs[i])) {
      edges.push_back(*e);
      ++(e->type == RegistrationEdgeType::kFeature ? report.feature_edges
                                                   : report.projection_edges);
      if (r.degenerate) ++report.degenerate_edges;
    } else {
      ++report.pairs_failed;
    }
  }
  const std::vector<RegistrationEdge> priors = PriorEdges(nodes, run.rig, options.priors);
  report.prior_edges = static_cast<int>(priors.size());
  edges.insert(edges.end(), priors.begin(), priors.end());

  const FusionResult fused = FuseRegistration(nodes, edges, options.fusion);
  report.fusion = fused.report;
  report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  report.seconds_per_node = report.seconds / report.nodes;
  // A resumed stage that registered nothing new and fused the same poses changes nothing
  // downstream (the later stages stay as they are).
  const std::filesystem::path poses = folder / "poses.csv";
  const std::string poses_before = IsRegularFile(poses) ? ReadTextFile(poses) : std::string();
  WriteRegistrationOutputs(folder, run.rig, nodes, edges, fused, options.length_scale_mm,
                           RegisterStageReportToJson(report));
  const bool changed = poses_before.empty() || ReadTextFile(poses) != poses_before;
  workspace.FinishStage(kStage, fused.report.usable,
                        {{"nodes", std::to_string(report.nodes)},
                         {"left_out", std::to_string(report.left_out.size())},
                         {"edges", std::to_string(edges.size())},
                         {"rejected", std::to_string(fused.report.rejected)}},
                        changed);
  return report;
}

}  // namespace sewer3d
