#include "sewer3d/sim/pipe_feature.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

using Type = PipeFeature::Type;

double At(const PipeFeature& f, double ds, double dclock = 0.0, double radius = 150.0) {
  return PipeFeatureDisplacementMm(f, ds, dclock, radius, 1, nullptr);
}

TEST(PipeFeature, ProfilesAtTheirCentreAndEdges) {
  PipeFeature crack{.type = Type::kCrack, .length_mm = 60.0, .width_mm = 2.0, .depth_mm = 3.0};
  EXPECT_DOUBLE_EQ(At(crack, 0.0), -3.0);                // V bottom
  EXPECT_DOUBLE_EQ(At(crack, 10.0, 0.5 / 150.0), -1.5);  // half-way up the V's side (0.5 of 1 mm)
  EXPECT_DOUBLE_EQ(At(crack, 31.0), 0.0);                // beyond its length
  PipeFeature bump{.type = Type::kBump, .height_mm = 6.0, .radius_mm = 4.0};
  EXPECT_DOUBLE_EQ(At(bump, 0.0), 6.0);
  EXPECT_NEAR(At(bump, 4.0), 6.0 * std::exp(-0.5), 1e-12);  // one sigma
  PipeFeature pit{.type = Type::kPit, .depth_mm = 4.0, .radius_mm = 10.0};
  EXPECT_DOUBLE_EQ(At(pit, 0.0), -4.0);
  EXPECT_DOUBLE_EQ(At(pit, 5.0), -3.0);  // paraboloid: 1 − (5/10)²
  EXPECT_DOUBLE_EQ(At(pit, 10.5), 0.0);
  PipeFeature joint{.type = Type::kJointStep, .depth_mm = 2.0, .gap_mm = 4.0, .offset_mm = 5.0};
  EXPECT_DOUBLE_EQ(At(joint, 0.0), -2.0);                          // in the gap
  EXPECT_DOUBLE_EQ(At(joint, -10.0), 0.0);                         // before it
  EXPECT_DOUBLE_EQ(At(joint, 10.0), 5.0);                          // beyond it, toward clock_h
  EXPECT_NEAR(At(joint, 10.0, std::numbers::pi / 2), 0.0, 1e-12);  // a quarter turn away
}

// A wet patch: a film without shape, full inside its rounded rectangle, none beyond its
// ragged margin (±3 mm at the shorter side, ±4.5 mm at the 1.5× longer one), thinning in
// between.
TEST(PipeFeature, AWetPatchIsAFilmWithoutShape) {
  const PipeFeature wet{
      .type = Type::kWet, .station_mm = 100.0, .length_mm = 40.0, .width_mm = 60.0};
  const double r = 150.0;
  const auto cover = [&](double ds, double arc) {
    return PipeFeatureWetCover(wet, ds, arc / r, r, 7);
  };
  EXPECT_EQ(At(wet, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(cover(0.0, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(cover(14.0, 20.0), 1.0);  // 5 mm in from both sides: beyond the margin
  for (const auto& [ds, arc] : {std::pair{23.0, 0.0}, {-23.0, 0.0}, {0.0, 34.5}, {0.0, -34.5}}) {
    EXPECT_EQ(cover(ds, arc), 0.0) << ds << ", " << arc;  // beyond the margin
  }
  EXPECT_EQ(PipeFeatureReachMm(wet), 20.0 * (1.0 + 3.0 / 20.0));
  // Along the side the margin wanders: the cover at the nominal edge takes many values.
  double low = 1.0, high = 0.0;
  for (double arc = -25.0; arc <= 25.0; arc += 0.5) {
    low = std::min(low, cover(20.0, arc));
    high = std::max(high, cover(20.0, arc));
  }
  EXPECT_LT(low, 0.2);
  EXPECT_GT(high, 0.8);
  // Only wet features make a film, the most of any that covers the point.
  const PipeFeature pit{.type = Type::kPit, .depth_mm = 4.0, .radius_mm = 10.0};
  const std::vector<PipeFeature> features = {pit, wet};
  EXPECT_DOUBLE_EQ(WetCover(features, 7, r, 100.0, [] { return 0.0; }), 1.0);
  EXPECT_EQ(WetCover(features, 7, r, 200.0, [] { return 0.0; }), 0.0);
  EXPECT_EQ(PipeFeatureTypeFromName("wet"), Type::kWet);
  EXPECT_THROW((PipeFeature{.type = Type::kWet, .length_mm = 10.0}.Check()), InvalidValue);
}

TEST(PipeFeature, ConnectionAndDepositBringTheirMaterial) {
  const std::vector<PipeFeature> features{{.type = Type::kConnection,
                                           .station_mm = 0.0,
                                           .clock_h = 3.0,
                                           .diameter_mm = 100.0,
                                           .wall_mm = 12.0,
                                           .intrusion_mm = 15.0},
                                          {.type = Type::kDeposit,
                                           .station_mm = 500.0,
                                           .clock_h = 6.0,
                                           .length_mm = 200.0,
                                           .height_mm = 20.0}};
  auto at = [&](double station, double clock_h, Material* m) {
    return AddPipeFeatures(
        0.0, features, 1, 150.0, station, [&] { return ClockHoursToRad(clock_h); }, m);
  };
  Material m = Material::kConcrete;
  EXPECT_NEAR(at(0.0, 3.0 + 56.0 / 150.0 * 6.0 / std::numbers::pi, &m), 15.0, 1e-9);  // its wall
  EXPECT_EQ(m, Material::kVitrifiedClay);
  m = Material::kConcrete;
  EXPECT_NEAR(at(0.0, 3.0, &m), -50.0, 1e-9);  // its open bore, modelled 50 mm deep
  EXPECT_EQ(m, Material::kConcrete);           // lowered, not raised: the wall's own material
  m = Material::kPlastic;
  EXPECT_GT(at(600.0, 6.0, &m), 19.0);  // the bed at the invert
  EXPECT_EQ(m, Material::kSediment);
  m = Material::kPlastic;
  EXPECT_EQ(at(300.0, 12.0, &m), 0.0);  // between them: plain wall
  EXPECT_EQ(m, Material::kPlastic);
}

TEST(PipeFeature, ClockIsOnlyComputedNearAFeature) {
  const std::vector<PipeFeature> features{{.type = Type::kCrack,
                                           .station_mm = 0.0,
                                           .length_mm = 10.0,
                                           .width_mm = 1.0,
                                           .depth_mm = 1.0}};
  int calls = 0;
  auto clock = [&] {
    ++calls;
    return 0.0;
  };
  EXPECT_EQ(AddPipeFeatures(0.0, features, 1, 150.0, 100.0, clock, nullptr), 0.0);
  EXPECT_EQ(calls, 0);
  EXPECT_DOUBLE_EQ(AddPipeFeatures(0.5, features, 1, 150.0, 0.0, clock, nullptr), -0.5);
  EXPECT_EQ(calls, 1);
}

TEST(PipeFeature, CheckNamesTheField) {
  try {
    PipeFeature{.type = Type::kCrack, .length_mm = 10.0, .width_mm = 1.0}.Check();
    FAIL() << "no throw";
  } catch (const InvalidValue& e) {
    EXPECT_EQ(e.field(), "depth_mm");
  }
  EXPECT_NO_THROW((PipeFeature{.type = Type::kPit, .radius_mm = 2.0}.Check()));
  EXPECT_THROW((PipeFeature{.type = Type::kBump}.Check()), InvalidValue);
}

}  // namespace
}  // namespace sewer3d
