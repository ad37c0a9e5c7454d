// The profile evaluation on a synthetic model of a known pipe: a round DN300 section, a joint,
// then a section deformed by 6 % at 12 o'clock with a deposit; the model's maps filled with the
// true wall (so its profile must agree with the true rings), its frame turned and shifted away
// from the world's by a known rigid transform. A displacement planted all over (+0.3 mm) must
// come back as the circumference error 0.3 / 150 = 0.2 % and a height error of 0.6 mm.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "sewer3d/simeval/profile_evaluation.hpp"

namespace sewer3d {
namespace {

constexpr double kPi = std::numbers::pi;

PipeWorld RoundThenOval() {
  PipeWorld w;
  PipeSection round;
  round.length_mm = 300.0;
  PipeSection oval = round;
  oval.length_mm = 400.0;
  oval.ovality_pct = 6.0;
  oval.ovality_clock_h = 12.0;
  oval.material = Material::kPlastic;
  w.sections = {round, oval};
  PipeJoint joint;
  joint.id = "J1";
  joint.gap_mm = 4.0;
  joint.gap_depth_mm = 2.0;
  w.joints = {joint};
  PipeFeature deposit;
  deposit.type = PipeFeature::Type::kDeposit;
  deposit.id = "D1";
  deposit.station_mm = 550.0;
  deposit.clock_h = 6.0;
  deposit.length_mm = 60.0;
  deposit.height_mm = 20.0;
  w.features = {deposit};
  return w;
}

struct SyntheticModel {
  Centreline centreline;
  PipeMaps maps;
};

/// The straight world pipe's model (axis = world z, crown = world −y) in a frame where the
/// world is `truth_from_model`; every cell holds the true wall's distance from the axis in its
/// clock direction (deformation and deposit depend only on station and clock) plus `planted`.
SyntheticModel MakeModel(const PipeGeometry& truth, const Rigid3d& truth_from_model,
                         float planted_mm) {
  const Rigid3d model_from_truth = truth_from_model.Inverse();
  SyntheticModel m;
  m.centreline.station0_mm = -50.0;
  m.centreline.radius_mm = 150.0;
  for (double s = -50.0; s <= 750.0; s += 10.0) {
    m.centreline.points.push_back(model_from_truth * Eigen::Vector3d(0.0, 0.0, s));
    m.centreline.crowns.push_back(model_from_truth.rotation * -Eigen::Vector3d::UnitY());
  }
  m.maps.grid = MakeMapGrid(5.0, 695.0, 150.0, 1.0);
  const MapGrid& g = m.maps.grid;
  m.maps.displacement_mm = cv::Mat1f(g.rows, g.cols);
  m.maps.coverage = cv::Mat1b(g.rows, g.cols, static_cast<unsigned char>(Coverage::kMeasured));
  for (int r = 0; r < g.rows; ++r) {
    for (int c = 0; c < g.cols; ++c) {
      const double a = g.ColClockRad(c);
      // Crown = −y, 3 o'clock = +x in the world (looking along +z).
      const Eigen::Vector3d p(150.0 * std::sin(a), -150.0 * std::cos(a), g.RowStationMm(r));
      const double wall = truth.WallRadiusMm(truth.Locate(p));
      m.maps.displacement_mm(r, c) = static_cast<float>(wall - 150.0) + planted_mm;
    }
  }
  return m;
}

const Rigid3d kTruthFromModel(
    Eigen::Quaterniond(Eigen::AngleAxisd(0.05, Eigen::Vector3d(1.0, 2.0, 0.5).normalized())),
    Eigen::Vector3d(12.0, -7.0, 30.0));

TEST(ProfileEvaluation, ExactModelAgreesWithTheTrueRings) {
  const PipeGeometry truth(RoundThenOval());
  const SyntheticModel m = MakeModel(truth, kTruthFromModel, 0.0f);
  const ProfileOptions profile_options;
  const Profile profile = ComputeProfile(m.maps, m.centreline.radius_mm, profile_options);
  ASSERT_EQ(profile.rows.size(), 69u);  // stations 10 … 690 mm
  const ProfileEvaluation e = EvaluateProfileAgainstTruth(profile, m.centreline, truth,
                                                          kTruthFromModel, profile_options, {});
  ASSERT_EQ(e.rows.size(), profile.rows.size());
  // Not clean: the joint at 300 ± (2 + 50) mm, the deposit over 550 … 610 mm ± 50 mm.
  int clean = 0;
  for (const ProfileRowEvaluation& r : e.rows) {
    EXPECT_NEAR(r.true_station_mm, r.station_mm, 1e-6);
    const bool near_joint = std::abs(r.station_mm - 300.0) <= 52.0;
    const bool near_deposit = r.station_mm >= 500.0 && r.station_mm <= 660.0;
    EXPECT_EQ(r.clean, !near_joint && !near_deposit) << r.station_mm;
    clean += r.clean ? 1 : 0;
    ASSERT_TRUE(std::isfinite(r.truth.circumference_mm)) << r.station_mm;
    if (!r.clean) continue;
    // The true rings: round (2π · 150) before the joint, 6 % oval well after it.
    if (r.station_mm < 250.0) {
      EXPECT_NEAR(r.truth.circumference_mm, 2.0 * kPi * 150.0, 0.02);
      EXPECT_NEAR(r.truth.ovality_en_pct, 0.0, 0.01);
    } else if (r.station_mm >= 400.0 && r.station_mm <= 600.0) {  // past the 100 mm ramps
      EXPECT_NEAR(r.truth.ovality_en_pct, 6.0, 0.02);
      EXPECT_NEAR(r.truth.height_mm, 282.0, 0.05);
    }
    // The model holds the true wall: its profile agrees far inside the acceptance.
    EXPECT_NEAR(r.circumference_error_pct, 0.0, 0.005) << r.station_mm;
    EXPECT_NEAR(r.ovality_en_error_pct, 0.0, 0.02) << r.station_mm;
    EXPECT_NEAR(r.ovality_astm_error_pct, 0.0, 0.02) << r.station_mm;
    EXPECT_NEAR(r.height_error_mm, 0.0, 0.05) << r.station_mm;
  }
  EXPECT_EQ(e.clean_rows, clean);
  EXPECT_EQ(clean, 69 - 11 - 17);
  EXPECT_EQ(e.circumference_pct.rows, clean);
  EXPECT_LT(e.circumference_pct.max, 0.005);
  EXPECT_LT(e.ovality_en_pct.p95, 0.02);
  // The deposit (20 mm at 6 o'clock) shows in the model's and the truth's height alike.
  const ProfileRowEvaluation& deposit = e.rows[57];  // station 580 mm
  ASSERT_DOUBLE_EQ(deposit.station_mm, 580.0);
  EXPECT_NEAR(deposit.truth.height_mm, 282.0 - 20.0, 0.5);
  EXPECT_NEAR(deposit.height_error_mm, 0.0, 0.05);
}

TEST(ProfileEvaluation, PlantedDisplacementShowsAsCircumferenceAndHeightError) {
  const PipeGeometry truth(RoundThenOval());
  const SyntheticModel m = MakeModel(truth, kTruthFromModel, 0.3f);
  const ProfileOptions profile_options;
  const Profile profile = ComputeProfile(m.maps, m.centreline.radius_mm, profile_options);
  const ProfileEvaluation e = EvaluateProfileAgainstTruth(profile, m.centreline, truth,
                                                          kTruthFromModel, profile_options, {});
  // 2π · 0.3 mm on about 2π · 150 mm: 0.2 %; diameters 0.6 mm longer.
  EXPECT_NEAR(e.circumference_pct.median, 0.2, 0.005);
  EXPECT_NEAR(e.circumference_pct.max, 0.2, 0.005);
  EXPECT_NEAR(e.height_mm.median, 0.6, 0.01);
  EXPECT_NEAR(e.mean_diameter_mm.median, 0.6, 0.01);
  EXPECT_LT(e.ovality_en_pct.max, 0.03);  // 6 % of 0.6 / 300 shifts the EN ovality by 0.012
  const auto json = nlohmann::json::parse(ProfileEvaluationToJson(e));
  EXPECT_EQ(json["clean_rows"].get<int>(), e.clean_rows);
  EXPECT_NEAR(json["circumference_pct"]["median_abs"].get<double>(), 0.2, 0.005);
  EXPECT_EQ(json["rows"].size(), profile.rows.size());
}

TEST(ProfileEvaluation, NoCleanStationGivesNullErrorsNotZeros) {
  const auto json = nlohmann::json::parse(ProfileEvaluationToJson(ProfileEvaluation{}));
  EXPECT_EQ(json["clean_rows"].get<int>(), 0);
  for (const char* field : {"median_abs", "p95_abs", "max_abs"})
    EXPECT_TRUE(json["circumference_pct"][field].is_null()) << field;
}

TEST(ProfileEvaluation, OptionsAreChecked) {
  ProfileEvaluationOptions o;
  o.ring_directions = 4;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.clean_margin_mm = -1.0;
  EXPECT_THROW(o.Check(), std::invalid_argument);
}

}  // namespace
}  // namespace sewer3d
