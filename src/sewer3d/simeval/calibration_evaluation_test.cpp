// The nearest module a file can hold for a lens the 3-term model cannot represent, and a
// calibration judged against it.

#include "sewer3d/simeval/calibration_evaluation.hpp"

#include <gtest/gtest.h>

#include <random>

#include "sewer3d/calib/camera_calibration.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

struct Captures {
  ModuleDescription truth = testing::SmallDefaultModule(2592);
  Checkerboard board;
  std::vector<Rigid3d> poses = RandomBoardPoses(truth, board, 20, 1);
};

// The paper profile's lenses without its projector's spot errors (those are the corners' noise
// here).
SpotErrors PaperLenses() {
  SpotErrors e;
  e.lens_residual = RealismProfile("paper")->lens_residual;
  return e;
}

TEST(CalibrationEvaluation, WithoutALensResidualTheNearestModuleIsTheTrueOne) {
  const Captures s;
  const ModuleCalibrationResult nearest =
      NearestFileModule(s.truth, SpotErrors{}, s.board, s.poses);
  EXPECT_NEAR(nearest.camera.cx, s.truth.camera.cx, 1e-6);
  EXPECT_NEAR(nearest.projector.cy, s.truth.projector.cy, 1e-6);
  EXPECT_NEAR(nearest.projector.fx, s.truth.projector.fx, 1e-6);
  EXPECT_LT(nearest.projector_rms_px, 1e-6);
}

// Corners seen through the paper profile's lenses with 0.1 px of detector noise: the calibration
// lands within its σ of the nearest file module, while the true projector principal point, which
// the decentring moves by over half a pixel, lies many σ away (docs/calibration.md).
TEST(CalibrationEvaluation, ACalibrationThroughTheResidualMeetsTheNearestModuleNotTheTrueOne) {
  const Captures s;
  const SpotErrors lenses = PaperLenses();
  const ModuleCalibrationResult nearest = NearestFileModule(s.truth, lenses, s.board, s.poses);
  // What the file cannot hold is a small fraction of a pixel, so the fit explains the corners.
  EXPECT_GT(nearest.projector_rms_px, 0.005);
  EXPECT_LT(nearest.projector_rms_px, 0.1);
  EXPECT_GT(std::abs(nearest.projector.cy - s.truth.projector.cy), 0.3);

  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.1);
  std::vector<ModuleCalibrationView> views =
      CornersThroughLenses(s.truth, lenses, s.board, s.poses);
  for (ModuleCalibrationView& v : views) {
    for (Eigen::Vector2d& q : v.camera_corners) q += Eigen::Vector2d(noise(rng), noise(rng));
    for (Eigen::Vector2d& u : v.projector_corners) u += Eigen::Vector2d(noise(rng), noise(rng));
  }
  const auto corners = BoardCorners(s.board.cols, s.board.rows, s.board.square_mm);
  const ModuleCalibrationResult r =
      CalibrateModule(views, corners, s.truth.camera.width, s.truth.camera.height,
                      s.truth.projector.width, s.truth.projector.height);
  ModuleDescription calibrated = s.truth;
  calibrated.camera = r.camera;
  calibrated.projector = r.projector;
  calibrated.projector_from_camera = r.projector_from_camera;
  const CalibrationEvaluation e = EvaluateCalibration(s.truth, nearest, calibrated, r.sigma);
  ASSERT_EQ(e.parameters.size(), 10U);
  // Ten parameters with Gaussian errors: each within 3 σ of the nearest module.
  for (const CalibrationParameter& p : e.parameters)
    EXPECT_LT(std::abs(p.error_to_nearest_sigmas), 3.0) << p.name;
  const CalibrationParameter& cy = e.parameters[7];
  EXPECT_EQ(cy.name, "projector cy");
  EXPECT_GT(std::abs(cy.error_sigmas), 4.0);
  EXPECT_GE(e.within_2_sigma_of_nearest, 9);
  EXPECT_LT(e.within_2_sigma, e.within_2_sigma_of_nearest);
}

}  // namespace
}  // namespace sewer3d
