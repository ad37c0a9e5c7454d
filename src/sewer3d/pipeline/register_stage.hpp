#pragma once
/// \file
/// The registration stage over a whole capture run (issue 15; DESIGN.md contract "processing
/// workspace"; docs/registration.md): every acquisition the RGB-D stage finished becomes a node
/// at its initial pose (odometry + rig); the carrier's offset from the pipe axis from the
/// first instant's walls; neighbour pairs registered (register_pairs.hpp, cached per pair);
/// rig, odometry and straightness edges; the robust fusion (register/fusion.hpp). Writes
/// WS/registration/poses.csv, graph.g2o, edges.csv, report.json and graph.png.
///
/// Acquisitions the RGB-D stage did not finish, or whose depth map has fewer than
/// `min_depth_points` points, are left out, each with its reason in the report.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "sewer3d/pipeline/register_pairs.hpp"
#include "sewer3d/pipeline/workspace.hpp"
#include "sewer3d/register/fusion.hpp"
#include "sewer3d/register/module_agreement.hpp"
#include "sewer3d/run/capture_run.hpp"

namespace sewer3d {

struct RegisterStageOptions {
  NeighbourOptions neighbours;  ///< its axis_in_model_mm is set by the stage from the walls
  PairRegistrationOptions pairs;
  PriorEdgeOptions priors;
  FusionOptions fusion;
  CarrierOffsetOptions carrier_offset;
  int min_depth_points = 200;  ///< fewer points in an acquisition's depth: left out
  int wall_step_px = 16;       ///< sampling of each instant's depth maps for the pipe's axis
  /// An instant's axis (its walls' circle) with a larger radial RMS is not used: walls that are
  /// no circle (a joint's step, an intrusion, a deformed pipe) do not say where the axis is.
  double axis_max_rms_mm = 1.0;
  /// Nor one whose robust fit kept less than this share of the points near its circle (a
  /// joint's step splits the walls into two circles).
  double axis_min_inliers = 0.8;
  double length_scale_mm = 150;  ///< L of the information eigenvalues in edges.csv
  int threads = 1;     ///< instants' walls and pairs worked on at once; does not change the outputs
  bool force = false;  ///< redo from scratch (Workspace::BeginStage)

  void Check() const;
};

/// The options that decide the outputs, as workspace.json records them (compact, sorted keys).
std::string RegisterOptionsJson(const RegisterStageOptions& options);

struct LeftOutAcquisition {
  int module = 0, counter = 0;
  std::string reason;
};

struct RegisterStageReport {
  int acquisitions = 0;  ///< with a pattern image (InitialPoses)
  int nodes = 0;         ///< in the graph
  std::vector<LeftOutAcquisition> left_out;
  InitialPosesReport initial;
  /// One line per problem of odometry.csv that LoadRun found (readings dropped because the
  /// distance went backwards; gaps longer than the bound, with the acquisitions in them).
  std::vector<std::string> odometry_warnings;
  CarrierOffsetEstimate carrier_offset;  ///< at the first counter
  int nodes_with_axis = 0;               ///< nodes whose instant's walls gave the pipe's axis
  NeighbourReport neighbours;
  int pairs = 0, pairs_done = 0, pairs_skipped = 0, pairs_failed = 0;
  int feature_edges = 0, projection_edges = 0, degenerate_edges = 0;
  int textured_edges = 0;  ///< projection edges with the photometric term
  int prior_edges = 0;
  FusionReport fusion;
  /// Per pair of modules with registrations between them: how many the gate rejected.
  std::vector<ModulePairAgreement> module_pairs;
  /// One line per pair of modules whose registrations contradict rig.json (RigWarnings).
  std::vector<std::string> rig_warnings;
  /// A line when the edges given leave the graph in unconnected parts (GraphWarning).
  std::vector<std::string> graph_warnings;
  double seconds = 0.0;           ///< the whole stage now, wall clock
  double seconds_per_pair = 0.0;  ///< mean over the pairs registered now (one worker)
  double seconds_per_node = 0.0;  ///< seconds / nodes
  int threads = 1;
};

/// The report as JSON text (format in docs/registration.md).
std::string RegisterStageReportToJson(const RegisterStageReport& report);

/// Progress of the stage's passes ("walls", "pairs"), never from two threads at once.
using RegisterProgress = std::function<void(const std::string& pass, int finished, int total)>;

/// Runs the registration stage of `run` into `workspace`. Throws std::invalid_argument on
/// invalid options, WorkspaceConflict (other options recorded, !force), FileError when the
/// workspace's files cannot be read or written. No acquisition usable: `nodes` 0, nothing
/// written, the stage recorded not done.
RegisterStageReport RunRegisterStage(const CaptureRun& run, Workspace& workspace,
                                     const RegisterStageOptions& options,
                                     const RegisterProgress& progress = {});

}  // namespace sewer3d
