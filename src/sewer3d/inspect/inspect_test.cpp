#include "sewer3d/inspect/inspect.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <opencv2/core.hpp>
#include <string>

#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/inspect/defects.hpp"
#include "sewer3d/model/axis_curve.hpp"

namespace sewer3d {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRadius = 150.0;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Signed clock difference (rad) in [−π, π).
double ClockDiff(double a, double b) { return std::remainder(a - b, 2.0 * kPi); }

// A DN300 pipe 600 mm long, straight along z, with one feature of each kind (displacement in
// mm, outward positive, as the model's maps hold it):
// - section 1 (s < 200): deformed 3 % toward 12 h (r = R − 4.5 cos 2θ), spalling 50 × 40 mm,
//   5 mm deep at s = 120, 4 h, its rim sloping to the wall over 2.5 mm more;
// - joint at s = 200: an 8 mm gap with no data in it; the next pipe 4 mm inward at 2 h and
//   its axis turned 1° toward 9 h;
// - a connection at s = 350, 10 h: bore Ø80 open 40 mm deep, its end 12 mm inward over a
//   10 mm wall; a crack at s = 450, 7.5 h, 100 mm long at 30° to the axis, 2 mm open, 3 mm deep;
//   a deposit 20 mm high at the invert from s = 480 to 580.
float Wall(double s, double th) {
  if (std::abs(s - 200.0) < 4.0) return kNaN;
  if (s < 200.0) {
    double d = -4.5 * std::cos(2.0 * th);
    const double arc = kRadius * ClockDiff(th, ClockHoursToRad(4.0));
    // The floor 50 x 40 mm, its rim sloping over 2.5 mm as a depth map blurs it.
    const double ramp = std::clamp((27.5 - std::abs(s - 120.0)) / 2.5, 0.0, 1.0) *
                        std::clamp((22.5 - std::abs(arc)) / 2.5, 0.0, 1.0);
    d += 5.0 * ramp;
    return static_cast<float>(d);
  }
  double d = -4.0 * std::cos(th - ClockHoursToRad(2.0)) +
             std::tan(DegToRad(1.0)) * (s - 200.0) * std::cos(th - ClockHoursToRad(9.0));
  const double arc_c = kRadius * ClockDiff(th, ClockHoursToRad(10.0)),
               rho = std::hypot(s - 350.0, arc_c);
  if (rho < 40.0) return static_cast<float>(d + 40.0);
  if (rho < 50.0) return static_cast<float>(d - 12.0);
  const double arc_k = kRadius * ClockDiff(th, ClockHoursToRad(7.5));
  const double a = DegToRad(30.0), along = (s - 450.0) * std::cos(a) + arc_k * std::sin(a);
  const double across = -(s - 450.0) * std::sin(a) + arc_k * std::cos(a);
  if (std::abs(along) < 50.0 && std::abs(across) < 1.0) d += 3.0 * (1.0 - std::abs(across));
  const double c = std::cos(ClockDiff(th, kPi));
  if (s > 480.0 && s < 580.0 && c > 0.0) d -= std::max(0.0, kRadius - (kRadius - 20.0) / c);
  return static_cast<float>(d);
}

// A DN300 pipe whose joint at s = 300 the depth maps bridged: no gap in the data, the next
// pipe's 4 mm step toward 12 h spread over ± 5 mm; from the joint that pipe's ovality (5 %,
// toward 12 h) grows over 100 mm, as the simulator's deformed sections do.
float BridgedJointWall(double s, double th) {
  const auto ramp = [](double u) {
    const double t = std::clamp(u, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
  };
  return static_cast<float>(-4.0 * ramp((s - 295.0) / 10.0) * std::cos(th) -
                            7.5 * ramp((s - 300.0) / 100.0) * std::cos(2.0 * th));
}

// A joint at s = 300 with an 8 mm gap that the depth maps bridged in 58 % of the columns (no
// lost spot fell into it there: a ramp to the next pipe, 3 mm inward at 12 h); open in the
// others.
float PartlyBridgedGapWall(double s, double th) {
  const bool open = std::sin(5.0 * th) > 0.25;
  if (open && std::abs(s - 300.0) < 4.0) return kNaN;
  const double t = std::clamp((s - 296.0) / 8.0, 0.0, 1.0);
  return static_cast<float>(-3.0 * t * t * (3.0 - 2.0 * t) * std::cos(th));
}

// A DN300 pipe with a spalled patch 60 × 40 mm, 5 mm deep, at s = 300, 4 h, whose rough floor
// lost most of its spots: measured only in islands ~5 mm across (a third of the floor), the
// rest unmeasured.
float HoledSpallWall(double s, double th) {
  const double arc = kRadius * ClockDiff(th, ClockHoursToRad(4.0));
  if (std::abs(s - 300.0) > 30.0 || std::abs(arc) > 20.0) return 0.0F;
  const bool island = std::sin(2.0 * kPi * s / 10.0) * std::sin(2.0 * kPi * arc / 10.0) > 0.5;
  return island ? 5.0F : kNaN;
}

// A DN300 pipe whose joint at s = 300 (a 6 mm gap with no data) has no offset: the next pipe
// is turned 1.5° toward 9 h.
float DeflectedJointWall(double s, double th) {
  if (std::abs(s - 300.0) < 3.0) return kNaN;
  return s < 300.0 ? 0.0F
                   : static_cast<float>(std::tan(DegToRad(1.5)) * (s - 300.0) *
                                        std::cos(th - ClockHoursToRad(9.0)));
}

// A DN300 pipe with a deposit 20 mm high at the invert from s = 250 to 400, its end ramped
// down over the last 30 mm: the steep part (s 370 … 392) lost its spots, the ramp's foot is
// measured only in islands; a flying-pixel clump stands 10 mm off the bed at 5.3 h, and a
// wrongly decoded island of 3 mm lies 76 mm behind the wall at s = 330, 6.5 h.
float RampedDepositWall(double s, double th) {
  const double c = std::cos(ClockDiff(th, kPi));
  if (s < 250.0 || s > 400.0 || c <= 0.0) return 0.0F;
  const double h = 20.0 * std::min(1.0, (400.0 - s) / 30.0);
  const double arc = kRadius * ClockDiff(th, kPi);
  if (s > 370.0 && (s < 392.0 || std::sin(arc / 4.0) < 0.0)) return kNaN;
  const double bed = std::max(0.0, kRadius - (kRadius - h) / c);
  const bool clump =
      std::abs(s - 300.0) < 2.5 && std::abs(ClockDiff(th, ClockHoursToRad(5.3))) * kRadius < 2.5;
  if (std::hypot(s - 330.0, ClockDiff(th, ClockHoursToRad(6.5)) * kRadius) < 1.5)
    return 76.0F;  // a wrongly decoded island far behind the wall: no connection's bore
  return static_cast<float>(-bed - (clump && bed > 0.0 ? 10.0 : 0.0));
}

// A DN300 pipe whose next pipe beyond the joint at s = 297 is turned 1° toward 9 h about the
// joint's centre: its end face turns with it, so the gap (6 mm at the axis, no data in it)
// opens to 6 + 2.6 mm at 3 h and closes to 6 − 2.6 mm at 9 h, where the depth maps bridged
// it wherever it is under 4 mm.
float TurnedGapWall(double s, double th) {
  const double t = std::tan(DegToRad(1.0));
  const double end = 303.0 + kRadius * t * std::cos(th - ClockHoursToRad(3.0));
  if (s > 297.0 && s < end && end - 297.0 >= 4.0) return kNaN;
  return s < 297.0 ? 0.0F
                   : static_cast<float>(t * std::max(0.0, s - 300.0) *
                                        std::cos(th - ClockHoursToRad(9.0)));
}

// A joint at s = 300 whose gap (8 mm) has its rough bottom (±0.4 mm) measured, 5 mm outward of
// the near pipe's wall, but for its first millimetre (in the near edge's shadow); the next pipe
// stands 4 mm outward at 12 h, so there the bottom lies only 1 mm below its wall (9 mm at 6 h).
float MeasuredBottomGapWall(double s, double th) {
  if (s < 296.0) return 0.0F;
  if (s < 297.0) return kNaN;
  if (s < 304.0) return static_cast<float>(5.0 + 0.4 * std::sin(4.8 * s) * std::sin(90.0 * th));
  return static_cast<float>(4.0 * std::cos(th));
}

CoarseMap SyntheticMap(double resolution_mm = 0.5, float (*wall)(double, double) = Wall) {
  const MapGrid grid = MakeMapGrid(0.0, 600.0, kRadius, resolution_mm);
  PipeMaps maps;
  maps.grid = grid;
  maps.displacement_mm.create(grid.rows, grid.cols);
  cv::Mat1f noise(grid.rows, grid.cols);
  cv::setRNGSeed(7);
  cv::randn(noise, 0.0, 0.05);  // a model's surface noise
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      maps.displacement_mm(r, c) = wall(grid.RowStationMm(r), grid.ColClockRad(c)) + noise(r, c);
    }
  }
  CoarseMapBuilder builder(grid, 1.0);
  builder.Add(maps);
  return builder.Finish();
}

Centreline Straight() {
  auto line = ResampleAxis({Eigen::Vector3d(0, 0, -20), Eigen::Vector3d(0, 0, 620)}, 10.0);
  EXPECT_TRUE(line.has_value());
  line->radius_mm = kRadius;
  line->station0_mm = -20.0;
  return *line;
}

InspectOptions WithDefects(const DefectOptions& defects) {
  InspectOptions options;
  options.defects = defects;
  return options;
}

const Observation* Only(const Inspection& in, const std::string& code) {
  const Observation* found = nullptr;
  for (const Observation& o : in.observations) {
    if (o.code != code) continue;
    EXPECT_EQ(found, nullptr) << "a second " << code << " at " << o.station_mm;
    found = &o;
  }
  EXPECT_NE(found, nullptr) << "no " << code;
  return found;
}

double Q(const Observation* o, const std::string& name) {
  const Quantity* q = o ? o->Find(name) : nullptr;
  EXPECT_NE(q, nullptr) << name;
  return q ? q->value : std::numeric_limits<double>::quiet_NaN();
}

TEST(Inspect, FindsAndMeasuresEveryKindOnASyntheticPipe) {
  const Inspection in = Inspect(SyntheticMap(), Straight(), {});
  EXPECT_EQ(in.observations.size(), 6U);
  for (const Observation& o : in.observations) {
    std::string q;
    for (const Quantity& x : o.quantities) q += " " + x.name + "=" + std::to_string(x.value);
    SCOPED_TRACE(o.id + " " + o.code + " at " + std::to_string(o.station_mm) + q);
    EXPECT_GT(o.confidence, 0.5);
  }
  const Observation* joint = Only(in, "BAJ");
  EXPECT_NEAR(joint->station_mm, 200.0, 1.0);
  EXPECT_NEAR(Q(joint, "offset_mm"), 4.0, 0.3);
  EXPECT_NEAR(joint->clock_h, 2.0, 0.25);
  EXPECT_NEAR(Q(joint, "gap_mm"), 8.0, 0.5);
  EXPECT_NEAR(Q(joint, "deflection_deg"), 1.0, 0.15);
  EXPECT_NEAR(Q(joint, "deflection_clock_h"), 9.0, 0.5);
  const Observation* connection = Only(in, "BAG");
  EXPECT_NEAR(connection->station_mm, 350.0, 2.0);
  EXPECT_NEAR(connection->clock_h, 10.0, 0.25);
  EXPECT_NEAR(Q(connection, "intrusion_mm"), 12.0, 0.5);
  EXPECT_NEAR(Q(connection, "bore_diameter_mm"), 80.0, 2.0);
  const Observation* spall = Only(in, "BAF");
  EXPECT_NEAR(spall->station_mm, 120.0, 2.0);
  EXPECT_NEAR(spall->clock_h, 4.0, 0.25);
  EXPECT_NEAR(Q(spall, "area_mm2"), 52.5 * 42.5, 300.0);  // out to the half-depth contour
  // The floor's depth: with the cells on the rim's slope (down to half depth) it reads 4.92.
  EXPECT_NEAR(Q(spall, "depth_mean_mm"), 5.0, 0.03);
  const Observation* crack = Only(in, "BAB");
  EXPECT_NEAR(crack->station_mm, 450.0, 3.0);
  EXPECT_NEAR(Q(crack, "length_mm"), 100.0, 10.0);
  EXPECT_NEAR(Q(crack, "angle_deg"), 30.0, 5.0);
  const Observation* deposit = Only(in, "BBC");
  EXPECT_NEAR(deposit->station_mm, 480.0, 3.0);
  EXPECT_NEAR(deposit->length_mm, 100.0, 6.0);
  EXPECT_NEAR(Q(deposit, "height_mm"), 20.0, 1.0);
  const Observation* deformation = Only(in, "BAA");
  EXPECT_NEAR(Q(deformation, "deformation_pct"), 3.0, 0.3);
  EXPECT_EQ(deformation->characterisation, "A");
  EXPECT_NEAR(deformation->station_mm, 0.0, 2.0);
  // It runs to the joint (the pipe deforms as a whole), not to the joint's band.
  EXPECT_NEAR(deformation->station_mm + deformation->length_mm, joint->station_mm, 0.5);
}

// The side lines start clear of the step's blur, and the change of shape along the next pipe
// (its second harmonic) is no deflection.
TEST(Inspect, MeasuresAJointWhoseGapWasBridged) {
  const Inspection in = Inspect(SyntheticMap(0.5, BridgedJointWall), Straight(), {});
  const Observation* joint = Only(in, "BAJ");
  ASSERT_NE(joint, nullptr);
  EXPECT_NEAR(joint->station_mm, 300.0, 2.0);
  EXPECT_NEAR(Q(joint, "offset_mm"), 4.0, 0.15);
  EXPECT_NEAR(std::remainder(joint->clock_h, 12.0), 0.0, 0.25);  // 12 h
  EXPECT_LT(Q(joint, "deflection_deg"), 0.1);
  EXPECT_TRUE(std::isnan(Q(joint, "gap_mm")));  // none in the data: not measured, not 0
  EXPECT_TRUE(std::isnan(Q(joint, "gap_depth_mm")));
  EXPECT_NE(joint->remark.find("gap not resolved in the maps"), std::string::npos) << joint->remark;
}

// The columns that bridge the gap say nothing of its width; the open ones do.
TEST(Inspect, MeasuresAGapFromItsOpenColumns) {
  const Inspection in = Inspect(SyntheticMap(0.5, PartlyBridgedGapWall), Straight(), {});
  const Observation* joint = Only(in, "BAJ");
  ASSERT_NE(joint, nullptr);
  EXPECT_NEAR(joint->station_mm, 300.0, 1.0);
  EXPECT_NEAR(Q(joint, "gap_mm"), 8.0, 0.5);
  EXPECT_NEAR(Q(joint, "offset_mm"), 3.0, 0.2);
}

// The islands of a spalled floor and the holes between them are one patch (session 44's
// full-size run reported such a patch as five, four of them "invented").
TEST(Inspect, MeasuresASpallWhoseFloorLostItsSpotsAsOnePatch) {
  const Inspection in = Inspect(SyntheticMap(0.5, HoledSpallWall), Straight(), {});
  ASSERT_EQ(in.observations.size(), 1U);
  const Observation* spall = Only(in, "BAF");
  ASSERT_NE(spall, nullptr);
  EXPECT_NEAR(spall->station_mm, 300.0, 2.0);
  EXPECT_NEAR(spall->clock_h, 4.0, 0.1);
  EXPECT_NEAR(Q(spall, "area_mm2"), 60.0 * 40.0, 0.15 * 2400.0);
  EXPECT_NEAR(Q(spall, "depth_mean_mm"), 5.0, 0.1);
  EXPECT_GT(Q(spall, "unmeasured_mm2"), 0.4 * 2400.0);
  DefectOptions islands_only;
  islands_only.max_hole_mm = 0.0;
  // Alone, every island (≤ 25 mm²) is under min_area_mm2: the patch would be missed.
  EXPECT_TRUE(Inspect(SyntheticMap(0.5, HoledSpallWall), Straight(), WithDefects(islands_only))
                  .observations.empty());
}

// A deflected joint's gap is its width at the axis: the mean of its widths around the turn,
// not their median, which leans toward the open side where the closing side is bridged.
TEST(Inspect, MeasuresADeflectedJointsGapAtTheAxis) {
  const Inspection in = Inspect(SyntheticMap(0.5, TurnedGapWall), Straight(), {});
  const Observation* joint = Only(in, "BAJ");
  ASSERT_NE(joint, nullptr);
  EXPECT_NEAR(Q(joint, "gap_mm"), 6.0, 0.3);
  EXPECT_NEAR(Q(joint, "deflection_deg"), 1.0, 0.15);
  EXPECT_NEAR(Q(joint, "deflection_clock_h"), 9.0, 0.5);
}

// A deposit's ramp islands are part of it, and its place is the middle of its bed (session
// 48's full-size run reported the ramp of its deposit as two more, "invented").
TEST(Inspect, MeasuresADepositWithItsRampIslandsAsOne) {
  const Inspection in = Inspect(SyntheticMap(0.5, RampedDepositWall), Straight(), {});
  ASSERT_EQ(in.observations.size(), 1U);
  const Observation* deposit = Only(in, "BBC");
  ASSERT_NE(deposit, nullptr);
  EXPECT_NEAR(deposit->station_mm, 250.0, 3.0);
  EXPECT_NEAR(deposit->length_mm, 150.0, 6.0);
  EXPECT_NEAR(deposit->clock_h, 6.0, 0.1);
  EXPECT_NEAR(Q(deposit, "height_mm"), 20.0, 1.0);
  DefectOptions apart;
  apart.deposit_join_mm = 0.0;
  EXPECT_GT(Inspect(SyntheticMap(0.5, RampedDepositWall), Straight(), WithDefects(apart))
                .observations.size(),
            1U);
}

// The gap's bottom counts as open against the wall of its own side: past the offset it lies
// less deep below the next pipe's wall than below this one's.
TEST(Inspect, MeasuresAGapWhoseBottomIsMeasuredPastAnOffset) {
  const Inspection in = Inspect(SyntheticMap(0.5, MeasuredBottomGapWall), Straight(), {});
  const Observation* joint = Only(in, "BAJ");
  ASSERT_NE(joint, nullptr);
  EXPECT_NEAR(joint->station_mm, 300.0, 0.5);
  EXPECT_NEAR(Q(joint, "gap_mm"), 8.0, 0.25);  // the bottom's old global reference: 6.85
  EXPECT_NEAR(Q(joint, "offset_mm"), 4.0, 0.15);
  EXPECT_NEAR(Q(joint, "gap_depth_mm"), 5.0, 0.5);
}

// A joint that is only deflected (BAJ C) is placed where its next pipe turns toward.
TEST(Inspect, PlacesADeflectedJointAtItsDeflectionsClock) {
  const Inspection in = Inspect(SyntheticMap(0.5, DeflectedJointWall), Straight(), {});
  const Observation* joint = Only(in, "BAJ");
  ASSERT_NE(joint, nullptr);
  EXPECT_EQ(joint->characterisation, "C");
  EXPECT_NEAR(Q(joint, "deflection_deg"), 1.5, 0.1);
  EXPECT_NEAR(joint->clock_h, 9.0, 0.25);
  EXPECT_LT(Q(joint, "offset_mm"), 0.2);
}

TEST(InteriorCells, ErodesARegionByAnEllipse) {
  std::vector<cv::Point> rect;  // 10 columns x 8 rows, at negative and positive coordinates
  for (int y = -3; y < 5; ++y) {
    for (int x = -4; x < 6; ++x) rect.emplace_back(x, y);
  }
  const std::vector<cv::Point> inner = InteriorCells(rect, 1, 2);
  ASSERT_EQ(inner.size(), 6U * 6U);
  for (const cv::Point& p : inner) {
    EXPECT_TRUE(p.x >= -2 && p.x < 4 && p.y >= -2 && p.y < 4) << p;
  }
  EXPECT_EQ(InteriorCells(rect, 0, 0).size(), rect.size());
  EXPECT_TRUE(InteriorCells(rect, 4, 0).empty());
  EXPECT_TRUE(InteriorCells({}, 1, 1).empty());
}

TEST(Inspect, MapsTooCoarseForTheThresholdsAreRefused) {
  // 5 mm cells: the 2 mm crack and the 8 mm gap are one or two cells; what such a map shows
  // would be invented shapes.
  EXPECT_THROW(Inspect(SyntheticMap(5.0), Straight(), {}), InvalidValue);
  InspectOptions coarse_cells;
  coarse_cells.cell_mm = 3.0;
  EXPECT_THROW(coarse_cells.Check(), InvalidValue);
}

}  // namespace
}  // namespace sewer3d
