// The model evaluation on a synthetic model of a known pipe: a straight DN300 pipe of concrete
// then plastic, a model written with WritePipeModel and read back, its frame turned and shifted
// away from the world's by a known rigid transform. The displacement planted (+0.3 mm over the
// concrete section, 0 over the plastic one; the 9–12 o'clock quarter marked filled) must come
// back as the per-material bias, per-coverage bias and circumference difference.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <opencv2/core.hpp>

#include "sewer3d/core/check.hpp"
#include "sewer3d/io/model_io.hpp"
#include "sewer3d/simeval/model_evaluation.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

constexpr double kPlanted_mm = 0.3;
constexpr double kSection_mm = 200.0;

PipeWorld TwoSections() {
  PipeWorld w;
  PipeSection concrete;
  concrete.length_mm = kSection_mm;
  concrete.material = Material::kConcrete;
  PipeSection plastic = concrete;
  plastic.material = Material::kPlastic;
  w.sections = {concrete, plastic};
  PipeJoint joint;
  joint.id = "J1";
  w.joints = {joint};
  return w;
}

/// The model of the straight world pipe (axis = world z, crown = world −y) in a frame where the
/// world is `truth_from_model`.
PipeModel SyntheticModel(const Rigid3d& truth_from_model) {
  const Rigid3d model_from_truth = truth_from_model.Inverse();
  Centreline centreline;
  centreline.station0_mm = -50.0;
  centreline.step_mm = 10.0;
  centreline.radius_mm = 150.0;
  for (double s = -50.0; s <= 2 * kSection_mm + 50.0; s += 10.0) {
    centreline.points.push_back(model_from_truth * Eigen::Vector3d(0.0, 0.0, s));
    centreline.crowns.push_back(model_from_truth.rotation * -Eigen::Vector3d::UnitY());
  }
  PipeMaps maps;
  maps.grid = MakeMapGrid(5.0, 2 * kSection_mm - 5.0, centreline.radius_mm, 1.0);
  const MapGrid& g = maps.grid;
  maps.texture = cv::Mat3b(g.rows, g.cols, cv::Vec3b(128, 128, 128));
  maps.samples = cv::Mat1w(g.rows, g.cols, 1);
  maps.displacement_mm = cv::Mat1f(g.rows, g.cols);
  maps.coverage = cv::Mat1b(g.rows, g.cols);
  for (int r = 0; r < g.rows; ++r) {
    for (int c = 0; c < g.cols; ++c) {
      maps.displacement_mm(r, c) = g.RowStationMm(r) < kSection_mm ? kPlanted_mm : 0.0f;
      const bool filled = g.ColClockRad(c) >= 1.5 * std::numbers::pi;
      maps.coverage(r, c) =
          static_cast<unsigned char>(filled ? Coverage::kFilled : Coverage::kMeasured);
    }
  }
  const fs::path dir = fs::temp_directory_path() / "sewer3d_model_evaluation_sim_test";
  fs::remove_all(dir);
  WritePipeModel(dir, centreline, maps, 0.0, {});
  PipeModel model = ReadPipeModel(dir);
  fs::remove_all(dir);
  return model;
}

TEST(ModelEvaluation, FindsThePlantedDisplacementPerMaterialCoverageAndCircumference) {
  const Rigid3d truth_from_model(
      Eigen::Quaterniond(Eigen::AngleAxisd(0.05, Eigen::Vector3d(1.0, 2.0, 0.5).normalized())),
      Eigen::Vector3d(12.0, -7.0, 30.0));
  const PipeGeometry truth(TwoSections());
  const PipeModel model = SyntheticModel(truth_from_model);
  ModelEvaluationOptions options;
  options.circumference_directions = 360;
  const ModelEvaluation e = EvaluatePipeModel(model, truth, truth_from_model, options);

  EXPECT_EQ(e.stride, 1);  // 0.37 M cells
  EXPECT_EQ(e.all.cells, static_cast<std::int64_t>(model.maps.grid.rows) * model.maps.grid.cols);
  ASSERT_EQ(e.by_material.size(), 2u);
  EXPECT_NEAR(e.by_material.at("concrete").mean_mm, kPlanted_mm, 0.02);
  EXPECT_NEAR(e.by_material.at("concrete").median_abs_mm, kPlanted_mm, 0.02);
  EXPECT_NEAR(e.by_material.at("plastic").mean_mm, 0.0, 0.02);
  EXPECT_NEAR(e.by_material.at("plastic").rms_mm, 0.0, 0.02);
  // Half of each coverage class lies over each section.
  ASSERT_EQ(e.by_coverage.size(), 2u);
  EXPECT_NEAR(e.by_coverage.at("measured").mean_mm, 0.5 * kPlanted_mm, 0.02);
  EXPECT_NEAR(e.by_coverage.at("filled").mean_mm, 0.5 * kPlanted_mm, 0.02);
  EXPECT_NEAR(static_cast<double>(e.by_coverage.at("filled").cells) / e.all.cells, 0.25, 0.01);
  EXPECT_NEAR(e.all.max_abs_mm, kPlanted_mm, 0.02);
  ASSERT_EQ(e.by_clock_hour.size(), 12u);
  for (const ErrorFigures& hour : e.by_clock_hour)
    EXPECT_NEAR(hour.mean_mm, 0.5 * kPlanted_mm, 0.02);

  // Cross-sections every 10 mm: 2π · 0.3 mm longer over the concrete, equal over the plastic
  // (but where a section's band of ± circumference_half_band_mm straddles the two).
  EXPECT_GE(e.circumference.sections, 38);
  for (const CircumferenceSample& s : e.circumference_profile) {
    if (std::abs(s.station_mm - kSection_mm) <= options.circumference_half_band_mm) continue;
    const double expected = s.station_mm < kSection_mm ? 2 * std::numbers::pi * kPlanted_mm : 0.0;
    EXPECT_NEAR(s.model_mm - s.truth_mm, expected, 0.02) << "station " << s.station_mm;
    EXPECT_NEAR(s.truth_mm, 2 * std::numbers::pi * 150.0, 0.1);
  }
  EXPECT_NEAR(e.circumference.max_abs_diff_mm, 2 * std::numbers::pi * kPlanted_mm, 0.02);

  const auto json = nlohmann::json::parse(ModelEvaluationToJson(e));
  EXPECT_NEAR(json["by_material"]["concrete"]["mean_mm"].get<double>(), kPlanted_mm, 0.02);
  const cv::Mat3b picture = ModelErrorMap(e, 1.0, 300);
  EXPECT_GT(picture.cols, 300);
  EXPECT_GT(picture.rows, 942 * 300 / model.maps.grid.rows);
}

TEST(ModelEvaluation, StrideSubsamplesTheCellsAndAWrongAlignmentShowsAsError) {
  const Rigid3d truth_from_model(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, 0));
  const PipeGeometry truth(TwoSections());
  const PipeModel model = SyntheticModel(truth_from_model);
  ModelEvaluationOptions options;
  options.stride = 4;
  const ModelEvaluation e = EvaluatePipeModel(model, truth, truth_from_model, options);
  EXPECT_EQ(e.error_mm.rows, (model.maps.grid.rows - 2 + 3) / 4);
  EXPECT_NEAR(static_cast<double>(e.all.cells), e.error_mm.total(), 0.5);
  EXPECT_NEAR(e.by_material.at("concrete").mean_mm, kPlanted_mm, 0.02);
  EXPECT_NEAR(e.axis_offset.max_abs_mm, 0.0, 0.01);
  // The model 1 mm off to the right: the wall errors swing ±1 mm around the clock.
  const Rigid3d shifted(Eigen::Quaterniond::Identity(), Eigen::Vector3d(1.0, 0, 0));
  const ModelEvaluation off = EvaluatePipeModel(model, truth, shifted, options);
  EXPECT_NEAR(off.by_material.at("plastic").max_abs_mm, 1.0, 0.02);
  EXPECT_NEAR(off.by_material.at("plastic").rms_mm, std::sqrt(0.5), 0.02);
  // … which the per-row axis offset takes out, leaving the planted displacement.
  EXPECT_NEAR(off.axis_offset.mean_mm, 1.0, 0.01);
  EXPECT_NEAR(off.axis_offset.max_abs_mm, 1.0, 0.01);
  EXPECT_NEAR(off.after_axis_offset_by_material.at("plastic").max_abs_mm, 0.0, 0.01);
  EXPECT_NEAR(off.after_axis_offset_by_material.at("concrete").mean_mm, kPlanted_mm, 0.01);
}

TEST(ModelEvaluation, PerCellNoiseLengthensTheRingOnlyByWhatItsSectorsKeep) {
  // Noise of σ per cell on a true round wall: adjacent sector means differ by Δ with
  // E[Δ²] = 2σ²/m (m cells per sector) over the chord ds = 2πR/n, so the polygon of n sectors
  // is longer by n · E[Δ²]/(2 ds) = n² σ² / (m · 2πR) on average. One row and one column per
  // direction (the raw polygon, m = 1): ~9.4 mm at σ = 0.1 mm, a 1 % error that is no wall's;
  // 1° sectors over ±1 mm (the default, m ≈ 7.9): ~0.17 mm.
  const Rigid3d identity;
  const PipeGeometry truth(TwoSections());
  PipeModel model = SyntheticModel(identity);
  constexpr double kSigma_mm = 0.1;
  cv::RNG rng(7);
  rng.fill(model.maps.displacement_mm, cv::RNG::NORMAL, 0.0, kSigma_mm);
  const MapGrid& g = model.maps.grid;
  auto expected = [&](int n, double cells_per_sector) {
    return n * n * kSigma_mm * kSigma_mm / (cells_per_sector * 2 * std::numbers::pi * 150.0);
  };
  ModelEvaluationOptions raw;
  raw.circumference_directions = g.cols;
  raw.circumference_half_band_mm = 0.0;
  const ModelEvaluation r = EvaluatePipeModel(model, truth, identity, raw);
  EXPECT_NEAR(r.circumference.mean_diff_mm, expected(g.cols, 1.0), 0.1 * expected(g.cols, 1.0));
  const ModelEvaluationOptions ring;
  const ModelEvaluation e = EvaluatePipeModel(model, truth, identity, ring);
  const double m = (g.cols / 360.0) *
                   (2.0 * std::floor(ring.circumference_half_band_mm / g.resolution_mm) + 1.0);
  EXPECT_GE(e.circumference.sections, 38);
  EXPECT_NEAR(e.circumference.mean_diff_mm, expected(360, m), 0.2 * expected(360, m));
  EXPECT_LT(e.circumference.max_abs_diff_mm, 0.05 * r.circumference.mean_diff_mm);
}

TEST(ModelEvaluation, AStrideThatEvaluatesTooManyCellsIsRefused) {
  // Memory grows with the cells evaluated: a stride of 1 on a fine map is refused with the
  // smallest stride that fits, not evaluated into gigabytes.
  const Rigid3d identity;
  const PipeGeometry truth(TwoSections());
  const PipeModel model = SyntheticModel(identity);
  const auto covered = static_cast<std::int64_t>(cv::countNonZero(model.maps.coverage));
  ModelEvaluationOptions options;
  options.stride = 1;
  options.target_cells = covered / 8;
  options.max_cells = covered / 4 + 1;  // stride 2 evaluates covered / 4
  try {
    EvaluatePipeModel(model, truth, identity, options);
    FAIL() << "stride 1 passed";
  } catch (const InvalidValue& e) {
    EXPECT_EQ(e.field(), "stride");
    EXPECT_NE(std::string(e.what()).find("at least 2"), std::string::npos) << e.what();
  }
  options.stride = 2;
  EXPECT_EQ(EvaluatePipeModel(model, truth, identity, options).stride, 2);
  options.stride = 0;
  EXPECT_EQ(EvaluatePipeModel(model, truth, identity, options).stride, 3);  // ceil(sqrt 8)
}

TEST(ModelEvaluation, FiguresOfNothingMeasuredAreNullNotZero) {
  const Rigid3d truth_from_model(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, 0));
  const PipeGeometry truth(TwoSections());
  PipeModel model = SyntheticModel(truth_from_model);
  // A quarter of the turn measured: no station for the axis offset, no whole cross-section.
  model.maps.coverage.colRange(model.maps.grid.cols / 4, model.maps.grid.cols).setTo(0);
  const ModelEvaluation e = EvaluatePipeModel(model, truth, truth_from_model, {});
  EXPECT_GT(e.all.cells, 0);
  EXPECT_EQ(e.axis_offset.cells, 0);
  EXPECT_EQ(e.circumference.sections, 0);
  const auto json = nlohmann::json::parse(ModelEvaluationToJson(e));
  EXPECT_TRUE(json["all"]["rms_mm"].is_number());
  EXPECT_TRUE(json["axis_offset"]["mean_mm"].is_null());
  EXPECT_TRUE(json["after_axis_offset"]["rms_mm"].is_null());
  EXPECT_TRUE(json["circumference"]["mean_diff_mm"].is_null());
}

}  // namespace
}  // namespace sewer3d
