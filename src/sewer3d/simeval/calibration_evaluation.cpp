#include "sewer3d/simeval/calibration_evaluation.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "sewer3d/calib/camera_calibration.hpp"
#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"

namespace sewer3d {
namespace {

// The camera pixel at which the renderer shows a point whose ideal image is `ideal`: the pixel
// p whose shifted ray p + shift(p) is the point's (fixed-point iteration; the shift is a
// fraction of a pixel and changes slowly over the image).
Eigen::Vector2d CameraImage(const LensResidual& residual, const CameraIntrinsics& camera,
                            const Eigen::Vector2d& ideal) {
  Eigen::Vector2d p = ideal;
  for (int i = 0; i < 4; ++i) p = ideal - residual.ShiftPx(camera, p);
  return p;
}

double BaselineMm(const Rigid3d& projector_from_camera) {
  return projector_from_camera.translation.norm();
}

double AngleDeg(const Rigid3d& a, const Rigid3d& b) {
  return RadToDeg(a.rotation.angularDistance(b.rotation));
}

}  // namespace

std::vector<ModuleCalibrationView> CornersThroughLenses(
    const ModuleDescription& truth, const SpotErrors& errors, const Checkerboard& board,
    const std::vector<Rigid3d>& camera_from_board) {
  const std::vector<Eigen::Vector3d> corners =
      BoardCorners(board.cols, board.rows, board.square_mm);
  const CameraModel camera(truth.camera), projector(truth.projector);
  const LensResidual camera_residual = MakeLensResidual(errors, 0);
  const LensResidual projector_residual = MakeLensResidual(errors, 1);
  std::vector<ModuleCalibrationView> views;
  for (const Rigid3d& pose : camera_from_board) {
    ModuleCalibrationView view;
    for (const Eigen::Vector3d& corner : corners) {
      const Eigen::Vector3d p = pose * corner;
      const auto in_camera = camera.Project(p);
      const auto in_projector = projector.Project(truth.projector_from_camera * p);
      SEWER3D_CHECK(in_camera && in_projector, "a board corner behind the camera or projector");
      view.camera_corners.push_back(CameraImage(camera_residual, truth.camera, *in_camera));
      // The element lighting a point is its ideal projector pixel shifted on (renderer).
      view.projector_corners.push_back(*in_projector +
                                       projector_residual.ShiftPx(truth.projector, *in_projector));
    }
    views.push_back(std::move(view));
  }
  return views;
}

ModuleCalibrationResult NearestFileModule(const ModuleDescription& truth, const SpotErrors& errors,
                                          const Checkerboard& board,
                                          const std::vector<Rigid3d>& camera_from_board) {
  return CalibrateModule(CornersThroughLenses(truth, errors, board, camera_from_board),
                         BoardCorners(board.cols, board.rows, board.square_mm), truth.camera.width,
                         truth.camera.height, truth.projector.width, truth.projector.height);
}

CalibrationEvaluation EvaluateCalibration(const ModuleDescription& truth,
                                          const ModuleCalibrationResult& nearest,
                                          const ModuleDescription& calibrated,
                                          const std::array<double, 10>& sigma) {
  CalibrationEvaluation e;
  e.nearest_camera_rms_px = nearest.camera_rms_px;
  e.nearest_projector_rms_px = nearest.projector_rms_px;
  const auto add = [&](const std::string& name, const std::string& unit, double t, double n,
                       double c, double s, double to_nearest) {
    CalibrationParameter p{name, unit, t, n, c, s};
    p.error_sigmas = s > 0.0 ? (c - t) / s : 0.0;
    p.error_to_nearest_sigmas = s > 0.0 ? to_nearest / s : 0.0;
    e.within_2_sigma += std::abs(p.error_sigmas) <= 2.0 ? 1 : 0;
    e.within_2_sigma_of_nearest += std::abs(p.error_to_nearest_sigmas) <= 2.0 ? 1 : 0;
    e.parameters.push_back(p);
  };
  const std::array<const CameraIntrinsics*, 3> camera{&truth.camera, &nearest.camera,
                                                      &calibrated.camera};
  const std::array<const CameraIntrinsics*, 3> projector{&truth.projector, &nearest.projector,
                                                         &calibrated.projector};
  int k = 0;
  for (const auto& [device, lens] :
       {std::pair{"camera", camera}, std::pair{"projector", projector}}) {
    for (const auto& [name, member] :
         {std::pair{"fx", &CameraIntrinsics::fx}, std::pair{"fy", &CameraIntrinsics::fy},
          std::pair{"cx", &CameraIntrinsics::cx}, std::pair{"cy", &CameraIntrinsics::cy}}) {
      const double t = lens[0]->*member, n = lens[1]->*member, c = lens[2]->*member;
      add(std::string(device) + " " + name, "px", t, n, c, sigma[k++], c - n);
    }
  }
  const double baseline = BaselineMm(calibrated.projector_from_camera);
  const double nearest_baseline = BaselineMm(nearest.projector_from_camera);
  add("baseline", "mm", BaselineMm(truth.projector_from_camera), nearest_baseline, baseline,
      sigma[8], baseline - nearest_baseline);
  const double to_nearest =
      AngleDeg(calibrated.projector_from_camera, nearest.projector_from_camera);
  const double angle = AngleDeg(calibrated.projector_from_camera, truth.projector_from_camera);
  add("rotation", "deg", 0.0, AngleDeg(nearest.projector_from_camera, truth.projector_from_camera),
      angle, sigma[9], to_nearest);
  return e;
}

std::string CalibrationEvaluationToJson(const CalibrationEvaluation& e,
                                        const std::string& realism) {
  nlohmann::json parameters = nlohmann::json::array();
  for (const CalibrationParameter& p : e.parameters) {
    parameters.push_back({{"name", p.name},
                          {"unit", p.unit},
                          {"true", p.truth},
                          {"nearest", p.nearest},
                          {"calibrated", p.calibrated},
                          {"sigma", p.sigma},
                          {"error_sigmas", p.error_sigmas},
                          {"error_to_nearest_sigmas", p.error_to_nearest_sigmas}});
  }
  const nlohmann::json j = {
      {"format", "sewer3d-calibration-evaluation"},
      {"realism", realism},
      {"nearest_rms_px",
       {{"camera", e.nearest_camera_rms_px}, {"projector", e.nearest_projector_rms_px}}},
      {"parameters", parameters},
      {"within_2_sigma", e.within_2_sigma},
      {"within_2_sigma_of_nearest", e.within_2_sigma_of_nearest}};
  return j.dump(2) + "\n";
}

}  // namespace sewer3d
