#pragma once
/// \file
/// A module calibrated from simulated checkerboard captures against the module the captures
/// were rendered with (docs/calibration.md). A real lens bends rays in ways the module file's
/// 3-term radial model cannot hold (the `paper` profile's lens residual: decentring and
/// thin-prism terms, docs/simulator.md). Calibrated through such a lens, the best a module
/// file can be is the nearest module it can hold: a decentring is absorbed by the principal
/// point and the extrinsic rotation, and what is absorbed leaves no residual for any
/// uncertainty to see. So each parameter is judged twice: against the true module, and
/// against that nearest module — the calibration of the same poses' exact corners seen through
/// the lenses (without a residual it is the true module).

#include <array>
#include <string>
#include <vector>

#include "sewer3d/calib/module_calibration.hpp"
#include "sewer3d/camera/module.hpp"
#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/sim/board.hpp"
#include "sewer3d/sim/spot_errors.hpp"

namespace sewer3d {

/// The board's exact corners at `camera_from_board` as the renderer shows them through the
/// lenses of `errors` (MakeLensResidual: the camera's image of a point shifted back, the
/// projector's element at a point shifted on), one view per pose.
std::vector<ModuleCalibrationView> CornersThroughLenses(
    const ModuleDescription& truth, const SpotErrors& errors, const Checkerboard& board,
    const std::vector<Rigid3d>& camera_from_board);

/// The module calibration of those exact corners: the nearest module a file can hold.
ModuleCalibrationResult NearestFileModule(const ModuleDescription& truth, const SpotErrors& errors,
                                          const Checkerboard& board,
                                          const std::vector<Rigid3d>& camera_from_board);

/// One parameter: its true value, the nearest file module's, the calibrated one's and the
/// calibration's standard deviation; errors in standard deviations. For the extrinsic rotation
/// the values are angles from the true rotation (deg) and error_to_nearest the angle between
/// the calibrated and the nearest rotation.
struct CalibrationParameter {
  std::string name, unit;
  double truth = 0.0, nearest = 0.0, calibrated = 0.0, sigma = 0.0;
  double error_sigmas = 0.0, error_to_nearest_sigmas = 0.0;
};

struct CalibrationEvaluation {
  /// camera fx fy cx cy, projector fx fy cx cy, baseline, rotation (ModuleCalibrationResult::
  /// sigma's order).
  std::vector<CalibrationParameter> parameters;
  /// RMS of the nearest module's fit: what the lenses bend that the file cannot hold (px).
  double nearest_camera_rms_px = 0.0, nearest_projector_rms_px = 0.0;
  int within_2_sigma = 0, within_2_sigma_of_nearest = 0;
};

/// `sigma`: the calibration's standard deviations in ModuleCalibrationResult::sigma's order.
CalibrationEvaluation EvaluateCalibration(const ModuleDescription& truth,
                                          const ModuleCalibrationResult& nearest,
                                          const ModuleDescription& calibrated,
                                          const std::array<double, 10>& sigma);

/// The evaluation as JSON text: realism, nearest_rms_px {camera, projector}, parameters [{name,
/// unit, true, nearest, calibrated, sigma, error_sigmas, error_to_nearest_sigmas}], within_2_sigma,
/// within_2_sigma_of_nearest.
std::string CalibrationEvaluationToJson(const CalibrationEvaluation& evaluation,
                                        const std::string& realism);

}  // namespace sewer3d
