// Two-pass module calibration on rendered checkerboard captures (sim/), rendered as `sewer3d
// simulate calibration` does (board lit with the pattern off at S = 4; pattern on with the
// ambient light off), at a quarter of the default size so that the test renders in seconds.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <string>

#include "sewer3d/calib/module_from_captures.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/sim/board.hpp"
#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

struct ParameterError {
  std::string name;
  double error = 0.0;  ///< calibrated − true
  double sigma = 0.0;  ///< the calibration's own standard deviation
};

// Every parameter with a standard deviation in ModuleCalibrationResult::sigma.
std::vector<ParameterError> Errors(const ModuleCalibrationResult& r,
                                   const ModuleDescription& truth) {
  const CameraIntrinsics &c = truth.camera, &p = truth.projector;
  const Eigen::Vector3d baseline = r.projector_from_camera.Inverse().translation;
  return {
      {"camera fx", r.camera.fx - c.fx, r.sigma[0]},
      {"camera fy", r.camera.fy - c.fy, r.sigma[1]},
      {"camera cx", r.camera.cx - c.cx, r.sigma[2]},
      {"camera cy", r.camera.cy - c.cy, r.sigma[3]},
      {"projector fx", r.projector.fx - p.fx, r.sigma[4]},
      {"projector fy", r.projector.fy - p.fy, r.sigma[5]},
      {"projector cx", r.projector.cx - p.cx, r.sigma[6]},
      {"projector cy", r.projector.cy - p.cy, r.sigma[7]},
      {"baseline mm", baseline.norm() - truth.projector_from_camera.Inverse().translation.norm(),
       r.sigma[8]},
      {"rotation deg",
       r.projector_from_camera.rotation.angularDistance(truth.projector_from_camera.rotation) *
           180.0 / M_PI,
       r.sigma[9]},
  };
}

// Sum of squared errors in standard deviations: one number for "closer to the truth".
double NormalisedSquaredError(const std::vector<ParameterError>& errors) {
  double sum = 0.0;
  for (const ParameterError& e : errors) sum += (e.error / e.sigma) * (e.error / e.sigma);
  return sum;
}

// One capture as `sewer3d simulate calibration` renders it: grey texture, 8-bit pattern.
std::pair<cv::Mat1b, cv::Mat1b> RenderCapture(const ModuleDescription& truth,
                                              const BinaryArray& pattern, const Checkerboard& board,
                                              const Rigid3d& pose, std::uint64_t seed) {
  const BoardSurface surface(board, pose);
  RenderOptions o;
  o.seed = seed;
  o.truth_depth = false;
  o.supersampling = 4;  // the board's edges alias below S = 4 (docs/calibration.md)
  o.images = RenderImages::kTexture;
  const RenderedFrame lit_board = RenderFrame(truth, pattern, surface, o);
  o.supersampling = 2;
  o.images = RenderImages::kPattern;
  o.ambient_level = 0.0;
  const RenderedFrame lit_pattern = RenderFrame(truth, pattern, surface, o);
  cv::Mat rgb8;
  cv::Mat1b texture_grey, pattern8;
  lit_board.texture.convertTo(rgb8, CV_8U);  // 8-bit sensor: digital numbers 0..255
  cv::cvtColor(rgb8, texture_grey, cv::COLOR_RGB2GRAY);
  lit_pattern.pattern.convertTo(pattern8, CV_8U);
  return {texture_grey, pattern8};
}

TEST(ModuleCalibrator, TwoPassesRecoverTheTrueModuleFromRenderedCaptures) {
  const ModuleDescription truth = testing::SmallDefaultModule(648);
  const BinaryArray pattern = DefaultPatternArray();
  // At a quarter of the default size the projector's pitch spans 4x the angle, so a 10 mm
  // square holds too few spots for the lattice (docs/calibration.md, "Seen, left"): 14 mm
  // squares, 8 x 5 corners to keep the board inside both fields.
  Checkerboard board;
  board.cols = 8;
  board.rows = 5;
  board.square_mm = 14.0;
  const int count = 12;
  const std::vector<Rigid3d> poses = RandomBoardPoses(truth, board, count, 1);
  ModuleCalibrator calibrator(truth, pattern, PatternConstraints{},
                              BoardLayout{board.cols, board.rows, board.square_mm});
  cv::Mat1b first_texture, first_pattern;  // the first capture used, given again below
  for (int i = 0; i < count; ++i) {
    const auto [texture_grey, pattern8] = RenderCapture(truth, pattern, board, poses[i], 1000 + i);
    const CaptureOutcome outcome = calibrator.AddCapture(texture_grey, pattern8);
    // Every pose shows the whole board; far ones may lose corners (too few spots on a square).
    EXPECT_NE(outcome.status, CaptureOutcome::Status::kBoardNotFound) << "pose " << i;
    EXPECT_EQ(outcome.corners, board.cols * board.rows) << "pose " << i;
    if (outcome.status == CaptureOutcome::Status::kCornersNotCarried) {
      EXPECT_GT(outcome.corners_missing, outcome.corners / 2) << "pose " << i;
    }
    if (outcome.status == CaptureOutcome::Status::kUsed && first_texture.empty()) {
      first_texture = texture_grey;
      first_pattern = pattern8;
    }
  }
  // The same capture again adds nothing: refused as a repeat of the first one used.
  const int used = calibrator.captures_used();
  const CaptureOutcome again = calibrator.AddCapture(first_texture, first_pattern);
  EXPECT_EQ(again.status, CaptureOutcome::Status::kRepeated);
  EXPECT_EQ(again.repeats, 0);
  EXPECT_EQ(calibrator.captures_used(), used);
  RecordProperty("captures_used", calibrator.captures_used());
  ASSERT_GE(calibrator.captures_used(), count / 2);
  const ModuleFromCapturesResult r = calibrator.Calibrate();
  EXPECT_TRUE(r.first_pass.converged);
  EXPECT_TRUE(r.second_pass.converged);
  EXPECT_EQ(r.views_retransferred, calibrator.captures_used());
  const auto first = Errors(r.first_pass, truth), second = Errors(r.second_pass, truth);
  for (size_t k = 0; k < second.size(); ++k) {
    std::printf("%-13s first pass %+.4f (sigma %.4f)  second pass %+.4f (sigma %.4f)\n",
                second[k].name.c_str(), first[k].error, first[k].sigma, second[k].error,
                second[k].sigma);
    // The sigmas scale the covariance by the corner residuals; the rendered corners' errors
    // are correlated over a board (aliasing, blur), which the sigmas do not see: 3 sigma.
    EXPECT_GT(second[k].sigma, 0.0) << second[k].name;
    EXPECT_LT(std::abs(second[k].error), 3.0 * second[k].sigma) << second[k].name;
  }
  // Corner noise on these renders is ~0.1 px per corner (docs/calibration.md: 0.11 px at
  // S = 4 against the true corners), so both RMS are about 0.1 px.
  std::printf("RMS camera %.4f / %.4f px, projector %.4f / %.4f px (first / second pass)\n",
              r.first_pass.camera_rms_px, r.second_pass.camera_rms_px,
              r.first_pass.projector_rms_px, r.second_pass.projector_rms_px);
  EXPECT_LT(r.second_pass.camera_rms_px, 0.15);
  EXPECT_LT(r.second_pass.projector_rms_px, 0.15);
  // The second pass removes the bending of pixel homographies by lens distortion: its
  // projector corners fit better, and it is no further from the truth.
  EXPECT_LE(r.second_pass.projector_rms_px, r.first_pass.projector_rms_px);
  const double first_error = NormalisedSquaredError(first);
  const double second_error = NormalisedSquaredError(second);
  std::printf("sum of squared errors in sigmas: first pass %.2f, second pass %.2f\n", first_error,
              second_error);
  EXPECT_LE(second_error, first_error);
  // The module carries the second pass's geometry over the nominal one.
  EXPECT_EQ(r.module.camera.fx, r.second_pass.camera.fx);
  EXPECT_EQ(r.module.projector.cy, r.second_pass.projector.cy);
  EXPECT_EQ(r.module.pattern.pitch_px, truth.pattern.pitch_px);
}

// The nominal module is a design: a projector 5 mm in front of where it says still lets the
// spots pick their tiles, so the captures carry their corners and calibration can begin.
TEST(ModuleCalibrator, ANominalModuleMillimetresOffStillCarriesTheCorners) {
  const ModuleDescription nominal = testing::SmallDefaultModule(648);
  ModuleDescription truth = nominal;
  truth.projector_from_camera.translation.z() += 5.0;
  const BinaryArray pattern = DefaultPatternArray();
  Checkerboard board;
  board.cols = 8;
  board.rows = 5;
  board.square_mm = 14.0;
  const std::vector<Rigid3d> poses = RandomBoardPoses(truth, board, 4, 2);
  ModuleCalibrator calibrator(nominal, pattern, PatternConstraints{},
                              BoardLayout{board.cols, board.rows, board.square_mm});
  ModuleCalibrator exact(truth, pattern, PatternConstraints{},
                         BoardLayout{board.cols, board.rows, board.square_mm});
  ModuleCalibratorOptions strict;
  strict.triangulation = TriangulationOptions{};  // 1 px: the test for a calibrated module
  strict.triangulation.adaptive_sigmas = 0.0;     // (not widened to the scatter the error makes)
  ModuleCalibrator tight(nominal, pattern, PatternConstraints{},
                         BoardLayout{board.cols, board.rows, board.square_mm}, strict);
  for (int i = 0; i < 4; ++i) {
    const auto [texture, pattern8] = RenderCapture(truth, pattern, board, poses[i], 2000 + i);
    const CaptureOutcome off = calibrator.AddCapture(texture, pattern8);
    const CaptureOutcome on = exact.AddCapture(texture, pattern8);
    const CaptureOutcome strict_outcome = tight.AddCapture(texture, pattern8);
    if (on.status != CaptureOutcome::Status::kUsed) continue;  // steep poses decode poorly
    // Nearly as many spots reach the corner transfer as with the true geometry; the 1 px test
    // of a calibrated module keeps few of them.
    EXPECT_GE(off.spots_decoded, 0.9 * on.spots_decoded) << "pose " << i;
    EXPECT_LT(strict_outcome.spots_decoded, 0.5 * on.spots_decoded) << "pose " << i;
  }
  EXPECT_GE(calibrator.captures_used(), 2);
}

}  // namespace
}  // namespace sewer3d
