#include "sewer3d/calib/module_from_captures.hpp"

#include <algorithm>
#include <cmath>

#include "sewer3d/calib/camera_calibration.hpp"
#include "sewer3d/calib/chessboard.hpp"
#include "sewer3d/core/check.hpp"

namespace sewer3d {

void BoardLayout::Check() const {
  SEWER3D_VALIDATE(cols >= 2 && rows >= 2, "board",
                   "needs at least 2x2 inner corners, got " << cols << "x" << rows);
  ValidatePositive("square_mm", square_mm);
}

void ModuleCalibratorOptions::Check() const {
  triangulation.Check();
  SEWER3D_VALIDATE(!corner_transfer.camera && !corner_transfer.projector, "corner_transfer",
                   "lens models must be unset: the second pass sets them");
  SEWER3D_VALIDATE(min_carried_fraction > 0.0 && min_carried_fraction <= 1.0,
                   "min_carried_fraction", "must be in (0, 1], got " << min_carried_fraction);
}

namespace {

TriangulationOptions TileTolerance(const ModuleCalibratorOptions& options,
                                   const ModuleDescription& nominal, const BinaryArray& pattern) {
  TriangulationOptions o = options.triangulation;
  const double between_tiles = nominal.pattern.pitch_px * std::min(pattern.rows, pattern.cols);
  o.max_reprojection_px = std::min(o.max_reprojection_px, 0.25 * between_tiles);
  return o;
}

}  // namespace

ModuleCalibrator::ModuleCalibrator(const ModuleDescription& nominal, const BinaryArray& pattern,
                                   const PatternConstraints& constraints, const BoardLayout& board,
                                   const ModuleCalibratorOptions& options)
    : nominal_(nominal),
      board_(board),
      options_(options),
      decoder_(nominal, pattern, constraints, options.decoder),
      triangulator_(nominal, pattern.rows, pattern.cols, TileTolerance(options, nominal, pattern)) {
  board_.Check();
  options_.Check();
}

CaptureOutcome ModuleCalibrator::AddCapture(const cv::Mat1b& texture_grey,
                                            const cv::Mat& pattern_image) {
  SEWER3D_VALIDATE(
      texture_grey.cols == nominal_.camera.width && texture_grey.rows == nominal_.camera.height,
      "texture",
      "is " << texture_grey.cols << "x" << texture_grey.rows << " but the nominal camera is "
            << nominal_.camera.width << "x" << nominal_.camera.height);
  CaptureOutcome outcome;
  const auto corners = DetectChessboard(texture_grey, board_.cols, board_.rows);
  if (!corners) {
    outcome.status = CaptureOutcome::Status::kBoardNotFound;
    return outcome;
  }
  outcome.corners = static_cast<int>(corners->size());
  std::vector<CalibrationView> used;
  for (const ModuleCalibrationView& v : views_) used.push_back({v.camera_corners});
  if (const int same = RepeatedView(used, {*corners}); same >= 0) {
    outcome.status = CaptureOutcome::Status::kRepeated;
    outcome.repeats = same;
    return outcome;
  }
  const std::vector<CodedObservation> observations =
      CodedObservations(decoder_.Decode(pattern_image));
  // Each decoded spot's projector element centre: exact, unlike the spot's camera centre.
  SpotCorrespondences spots;
  for (const TriangulatedPoint& p : triangulator_.Triangulate(observations, nullptr)) {
    spots.camera_px.push_back(observations[p.observation].camera_px);
    spots.projector_px.push_back(nominal_.pattern.ElementCentre(p.row, p.col));
  }
  outcome.spots_decoded = static_cast<int>(spots.camera_px.size());
  const auto transferred =
      CornersInProjector(*corners, spots.camera_px, spots.projector_px, options_.corner_transfer);
  outcome.corners_missing = static_cast<int>(
      std::count_if(transferred.begin(), transferred.end(), [](const auto& c) { return !c; }));
  const int carried = outcome.corners - outcome.corners_missing;
  if (carried < options_.min_carried_fraction * outcome.corners) {
    outcome.status = CaptureOutcome::Status::kCornersNotCarried;
    return outcome;
  }
  ModuleCalibrationView view;
  view.camera_corners = *corners;
  for (const auto& c : transferred)
    view.projector_corners.push_back(c ? *c : Eigen::Vector2d::Constant(std::nan("")));
  views_.push_back(std::move(view));
  spots_.push_back(std::move(spots));
  return outcome;
}

ModuleFromCapturesResult ModuleCalibrator::Calibrate() const {
  SEWER3D_VALIDATE(views_.size() >= 3, "captures",
                   views_.size() << " captures used; calibration needs at least 3");
  const auto board = BoardCorners(board_.cols, board_.rows, board_.square_mm);
  const auto calibrate = [&](const std::vector<ModuleCalibrationView>& views) {
    return CalibrateModule(views, board, nominal_.camera.width, nominal_.camera.height,
                           nominal_.projector.width, nominal_.projector.height);
  };
  ModuleFromCapturesResult result;
  result.first_pass = calibrate(views_);
  // Second pass: the homographies fitted between undistorted coordinates, where a plane's
  // camera -> projector map is exactly one (lens distortion bends it in pixels).
  std::vector<ModuleCalibrationView> views = views_;
  result.views_retransferred =
      RetransferCorners(views, spots_, result.first_pass.camera, result.first_pass.projector,
                        options_.corner_transfer);
  result.second_pass = calibrate(views);
  result.module = nominal_;
  result.module.camera = result.second_pass.camera;
  result.module.projector = result.second_pass.projector;
  result.module.projector_from_camera = result.second_pass.projector_from_camera;
  return result;
}

}  // namespace sewer3d
