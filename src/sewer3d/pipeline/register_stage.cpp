#include "sewer3d/pipeline/register_stage.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <nlohmann/json.hpp>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/registration_io.hpp"
#include "sewer3d/io/rgbd_io.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/pipeline/parallel_items.hpp"
#include "sewer3d/pipeline/register_outputs.hpp"
#include "sewer3d/pipeline/register_warnings.hpp"
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

/// The pipe's axis at every counter from the walls of its nodes (EstimateCarrierOffset; the
/// counters on options.threads workers, each reading its nodes' depth maps); each node whose
/// instant gave one, with a fit within `axis_max_rms_mm` that kept at least
/// `axis_min_inliers` of its points, gets the axis point in its camera frame. Returns the first
/// counter's estimate.
CarrierOffsetEstimate InstantAxes(std::vector<AcquisitionNode>& nodes, const CaptureRun& run,
                                  const std::filesystem::path& rgbd_folder,
                                  const RegisterStageOptions& options,
                                  const RegisterProgress& progress) {
  std::map<int, std::vector<size_t>> per_counter;
  for (size_t i = 0; i < nodes.size(); ++i) per_counter[nodes[i].counter].push_back(i);
  const std::vector<std::pair<const int, std::vector<size_t>>> counters(per_counter.begin(),
                                                                        per_counter.end());
  std::vector<CarrierOffsetEstimate> axes(counters.size());
  ForEachItem<int>(
      counters.size(), options.threads, [] { return 0; },
      [&](size_t k, int&) {
        std::vector<ModuleWallPoints> walls;
        for (size_t i : counters[k].second) {
          const AcquisitionNode& n = nodes[i];
          const CameraModel camera(run.rig.modules[n.module].module.camera);
          walls.push_back(
              {n.module, SampleDepthPoints(ReadRgbdDepth(rgbd_folder, n.module, n.counter), camera,
                                           options.wall_step_px)});
        }
        axes[k] = EstimateCarrierOffset(run.rig, walls, options.carrier_offset);
      },
      [&](int finished) {
        if (progress) progress("walls", finished, static_cast<int>(counters.size()));
      });
  for (size_t k = 0; k < counters.size(); ++k) {
    const CarrierOffsetEstimate& axis = axes[k];
    if (!axis.valid || axis.rms_mm > options.axis_max_rms_mm ||
        axis.inlier_fraction < options.axis_min_inliers)
      continue;
    const Eigen::Vector3d in_carrier(axis.axis_in_carrier_mm.x(), axis.axis_in_carrier_mm.y(),
                                     axis.mean_z_mm);
    for (size_t i : counters[k].second) {
      nodes[i].axis_in_camera =
          run.rig.modules[nodes[i].module].carrier_from_camera.Inverse() * in_carrier;
    }
  }
  return axes.empty() ? CarrierOffsetEstimate{} : axes.front();
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
  ValidatePositive("axis_max_rms_mm", axis_max_rms_mm);
  SEWER3D_VALIDATE(axis_min_inliers >= 0.0 && axis_min_inliers <= 1.0, "axis_min_inliers",
                   "must be within [0, 1], got " << axis_min_inliers);
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
  std::vector<AcquisitionNode> nodes =
      UsableNodes(initial.nodes, rgbd_folder, options.min_depth_points, report);
  report.nodes = static_cast<int>(nodes.size());
  if (nodes.empty()) {  // nothing to register: the outcome says why, nothing is written
    report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    workspace.FinishStage(kStage, false,
                          {{"nodes", "0"}, {"left_out", std::to_string(report.left_out.size())}});
    return report;
  }

  NeighbourOptions neighbours = options.neighbours;
  report.carrier_offset = InstantAxes(nodes, run, rgbd_folder, options, progress);
  for (const AcquisitionNode& n : nodes) report.nodes_with_axis += n.axis_in_camera ? 1 : 0;
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
    if (const std::optional<RegistrationEdge> e = PairEdge(r, pairs.pairs[i], options.pairs)) {
      edges.push_back(*e);
      ++(e->type == RegistrationEdgeType::kFeature ? report.feature_edges
                                                   : report.projection_edges);
      if (r.degenerate) ++report.degenerate_edges;
      if (r.photometric) ++report.textured_edges;
    } else {
      ++report.pairs_failed;
    }
  }
  const std::vector<RegistrationEdge> priors = PriorEdges(nodes, run.rig, options.priors);
  report.prior_edges = static_cast<int>(priors.size());
  edges.insert(edges.end(), priors.begin(), priors.end());

  if (std::string parts = GraphWarning(static_cast<int>(nodes.size()), edges); !parts.empty())
    report.graph_warnings.push_back(std::move(parts));
  const FusionResult fused = FuseRegistration(nodes, edges, options.fusion);
  report.fusion = fused.report;
  report.module_pairs = ModulePairAgreements(nodes, edges, fused);
  report.rig_warnings = RigWarnings(run, report.module_pairs);
  if (std::string carrier = CarrierWarning(run, report.carrier_offset); !carrier.empty())
    report.rig_warnings.push_back(std::move(carrier));
  const EdgeTypeStatistics& odometry =
      fused.report.by_type[static_cast<int>(RegistrationEdgeType::kOdometry)];
  if (std::string rejected = OdometryRejectedWarning(run, odometry); !rejected.empty())
    report.odometry_warnings.push_back(std::move(rejected));
  else if (std::string along = AlongWarning(run, AlongAgreement(nodes, edges, fused));
           !along.empty())
    report.odometry_warnings.push_back(std::move(along));
  else if (std::string fit = OdometryFitWarning(run, odometry); !fit.empty())
    report.odometry_warnings.push_back(std::move(fit));
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
