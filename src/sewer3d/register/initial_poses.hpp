#pragma once
/// \file
/// Initial camera poses of a run's acquisitions from odometry and the rig (paper §4.1), and
/// the carrier's offset from the pipe axis from the six modules' walls at one instant.
///
/// **Model frame** (the frame of WS/registration/poses.csv): origin at the carrier centre at
/// the time of the run's first image, z along the pipe (the carrier's axis, forward), y down
/// and x right as the carrier's frame (run/rig.hpp) was at that instant. Odometry only knows
/// the distance travelled, so the initial guess moves the carrier straight along model z
/// without turning: world_from_carrier(t) = translation (0, 0, d(t) − d(t₀)), with d the cable
/// counter's distance, and world_from_camera = world_from_carrier · carrier_from_camera.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "sewer3d/core/circle_fit.hpp"
#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/run/capture_run.hpp"

namespace sewer3d {

/// A node of the registration graph: one acquisition's camera at its pattern instant.
struct AcquisitionNode {
  int module = 0;
  int counter = 0;
  double time_s = 0.0;       ///< the pattern image's time
  double distance_mm = 0.0;  ///< odometry distance at time_s, relative to the first image
  /// Where time_s lies in a gap of the odometry (CaptureRun::odometry_findings): σ of
  /// distance_mm and of the carrier's speed there beyond what a reading has (0 elsewhere).
  double distance_sigma_mm = 0.0;
  double speed_sigma_mm_s = 0.0;
  Rigid3d world_from_camera;  ///< model frame
  /// Gravity's direction in the camera frame at time_s from the run's inclinometer (unit);
  /// nullopt where the run has none (or no reading around time_s).
  std::optional<Eigen::Vector3d> down_in_camera;
  /// A point of the pipe's axis in the camera frame (mm), from the walls of the node's instant
  /// (EstimateCarrierOffset); nullopt where they gave none. Set by the registration stage.
  std::optional<Eigen::Vector3d> axis_in_camera;
};

struct InitialPosesReport {
  int acquisitions = 0;        ///< grouped from the run's images
  int nodes = 0;               ///< with a pattern image, hence a pose
  int without_pattern = 0;     ///< skipped: no pattern image
  int outside_odometry = 0;    ///< time outside the odometry's span: nearest reading used
  int odometry_backwards = 0;  ///< consecutive readings (of those kept) whose distance decreases
  int odometry_dropped = 0;    ///< readings LoadRun dropped: the distance went backwards
  int in_odometry_gap = 0;     ///< nodes placed by interpolation across a long gap
  int with_inclinometer = 0;   ///< nodes with the direction of gravity (down_in_camera)
  double first_image_time_s = 0.0;
};

struct InitialPosesResult {
  std::vector<AcquisitionNode> nodes;  ///< ordered by (module, counter)
  InitialPosesReport report;
};

/// The initial guess for every acquisition with a pattern image. Throws std::invalid_argument
/// when the run has no odometry reading, no image, or an image names a module the rig lacks.
InitialPosesResult InitialPoses(const CaptureRun& run);

/// One module's wall points at (about) one instant, in its camera frame (mm).
struct ModuleWallPoints {
  int module = 0;
  std::vector<Eigen::Vector3d> points_in_camera;
};

struct CarrierOffsetOptions {
  int min_points = 30;  ///< in all, and on the circle
  int min_modules = 3;  ///< with at least one point: the circle needs the angles spread
  /// The circle (FitCircleRobust): round (a module's arc cannot tell an oval), Tukey weights
  /// on a MAD scale, so an intrusion or a joint's far side leaves it.
  CircleFitOptions circle{.model_ovality = false};
  /// The inlier share is taken of the points within this of the circle.
  double outlier_mm = 5.0;

  void Check() const;
};

/// A circle fitted to the walls around the carrier, in the carrier's x-y plane.
struct CarrierOffsetEstimate {
  bool valid = false;
  /// Where the pipe axis crosses the carrier's x-y plane (carrier frame, mm); the carrier
  /// centre's offset from the pipe axis is its negative.
  Eigen::Vector2d axis_in_carrier_mm = Eigen::Vector2d::Zero();
  double diameter_mm = 0.0;
  /// The mean carrier z of the points used (mm): (axis_in_carrier_mm, mean_z_mm) is a point of
  /// the axis where the walls were seen, whatever the carrier's tilt.
  double mean_z_mm = 0.0;
  double rms_mm = 0.0;  ///< radial residual of the points used
  int points = 0;       ///< used
  /// Of the points within outlier_mm of the circle, the share it kept (non-zero weight).
  double inlier_fraction = 0.0;
  int modules = 0;  ///< contributing
};

/// Fits the pipe's cross-section to the modules' wall points mapped into the carrier frame
/// (rig's carrier_from_camera) and projected along the carrier axis: the robust circle fit of
/// core/circle_fit.hpp (CarrierOffsetOptions::circle). Assumes the pipe
/// axis is parallel to the carrier's (a tilt of α widens the circle by 1/cos α along it).
/// `valid` false with too few points or modules. Throws std::invalid_argument for a module
/// index the rig lacks or bad options.
CarrierOffsetEstimate EstimateCarrierOffset(const Rig& rig,
                                            const std::vector<ModuleWallPoints>& walls,
                                            const CarrierOffsetOptions& options = {});

}  // namespace sewer3d
