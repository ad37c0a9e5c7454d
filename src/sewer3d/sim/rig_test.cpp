// Rig geometry and overlap, robot motion, capture plan and odometry of a virtual run.

#include "sewer3d/sim/rig.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/sim/odometry.hpp"
#include "sewer3d/sim/scenario.hpp"
#include "sewer3d/sim/trajectory.hpp"

namespace sewer3d {
namespace {

Rig DefaultRig() { return MakeRig(MakeDefaultModule({}), {}); }

TEST(Rig, SixModulesAroundTheAxisInsideTheCarrier) {
  const Rig rig = DefaultRig();
  ASSERT_EQ(rig.modules.size(), 6u);
  for (size_t k = 0; k < 6; ++k) {
    const RigModule& m = rig.modules[k];
    const Eigen::Matrix3d r = m.carrier_from_camera.RotationMatrix();
    EXPECT_NEAR((r.transpose() * r - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
    // Looks radially at its clock position; camera y along the carrier axis.
    EXPECT_NEAR((r.col(2) - ClockDirection(DegToRad(60.0 * k))).norm(), 0.0, 1e-9);
    EXPECT_NEAR(r.col(1).z(), 1.0, 1e-12);
    // Camera and projector centres on the axis, within the carrier's length.
    const Eigen::Vector3d c = m.carrier_from_camera.translation, p = ProjectorCentreInCarrier(m);
    EXPECT_NEAR(std::hypot(c.x(), c.y()), 0.0, 1e-9);
    EXPECT_NEAR(std::hypot(p.x(), p.y()), 0.0, 1e-6);
    EXPECT_LE(std::max(std::abs(c.z()), std::abs(p.z())), 300.0);
    if (k > 0) {
      EXPECT_NEAR(c.z() - rig.modules[k - 1].carrier_from_camera.translation.z(), 90.0, 1e-9);
    }
  }
  RigOptions crowded;
  crowded.stagger_mm = 120.0;
  EXPECT_THROW(MakeRig(MakeDefaultModule({}), crowded), std::invalid_argument);
}

TEST(Rig, NeighboursOverlapForEveryDiameterAndDecentring) {
  DefaultModuleOptions small;
  small.camera_width = 648;  // same angles as the full module, 16x fewer rays
  small.camera_height = 486;
  const Rig rig = MakeRig(MakeDefaultModule(small), {});
  struct Case {
    double diameter;
    Eigen::Vector2d offset;
  };
  const Case cases[] = {{200, {0, 0}},  {300, {0, 0}},  {400, {0, 0}},    {200, {0, 20}},
                        {300, {25, 0}}, {300, {0, 25}}, {400, {-18, 18}}, {400, {0, -25}}};
  for (const Case& c : cases) {
    for (const bool lit : {false, true}) {
      double worst = 1e9, worst_mm = 0.0;
      for (const NeighbourOverlap& o : NeighbourOverlaps(rig, c.diameter, c.offset, lit)) {
        if (o.overlap_deg < worst) worst = o.overlap_deg, worst_mm = o.overlap_mm;
      }
      std::printf(
          "DN%.0f offset (%+.0f, %+.0f) mm, %s: smallest neighbour overlap %.1f deg = %.1f mm\n",
          c.diameter, c.offset.x(), c.offset.y(),
          lit ? "3-D (camera+projector)" : "texture (camera)", worst, worst_mm);
      EXPECT_GT(worst, 5.0);
      EXPECT_GT(worst_mm, 5.0);
    }
  }
}

TEST(Rig, NeighboursOverlapInEveryPreset) {
  for (const std::string& name : PresetNames()) {
    const Scenario s = PresetScenario(name);
    DefaultModuleOptions options;
    options.camera_width = s.camera_width;
    options.camera_height = s.camera_width * 3 / 4;
    const Rig rig = MakeRig(MakeDefaultModule(options), s.rig);
    const double worst_offset = s.motion.offset_mm.norm() + std::sqrt(2.0) * s.motion.wander_mm;
    for (const PipeSection& section : s.world.sections) {
      for (const Eigen::Vector2d& offset :
           {Eigen::Vector2d(s.motion.offset_mm), Eigen::Vector2d(0.0, worst_offset),
            Eigen::Vector2d(worst_offset, 0.0)}) {
        double worst = 1e9;
        for (const NeighbourOverlap& o :
             NeighbourOverlaps(rig, section.diameter_mm, offset, true, s.camera_width / 80)) {
          worst = std::min(worst, o.overlap_deg);
        }
        std::printf(
            "preset %-4s DN%.0f carrier offset (%+.1f, %+.1f) mm: smallest 3-D neighbour overlap "
            "%.1f deg\n",
            name.c_str(), section.diameter_mm, offset.x(), offset.y(), worst);
        EXPECT_GT(worst, 5.0);
      }
    }
  }
}

TEST(Trajectory, FollowsThePipeWithOffsetRollAndWobble) {
  PipeWorld w;
  w.sections = {{.length_mm = 3000.0, .diameter_mm = 300.0}};
  const PipeGeometry pipe(w);
  MotionOptions o;
  o.travel_mm = 1000.0;
  const Trajectory tr(pipe, o, 7);
  EXPECT_NEAR(tr.StationAt(0.0), o.start_station_mm, 1e-9);
  EXPECT_NEAR(tr.StationAt(tr.DurationS()), o.start_station_mm + 1000.0, 1e-6);
  EXPECT_NEAR(tr.DurationS(), 10.0, 1.0);  // 100 mm/s ± 5 %
  for (double t = 0.0; t < tr.DurationS(); t += 0.37) {
    const Rigid3d p = tr.WorldFromCarrier(t);
    EXPECT_NEAR(p.translation.z(), tr.StationAt(t), 1e-9);
    const double decentring = std::hypot(p.translation.x() - 0.0, p.translation.y() - 15.0);
    EXPECT_LE(decentring, std::sqrt(2.0) * o.wander_mm + 1e-9);
    const Eigen::Vector3d axis = p.rotation * Eigen::Vector3d::UnitZ();
    EXPECT_LE(RadToDeg(std::acos(std::min(1.0, axis.z()))), std::sqrt(2.0) * o.wobble_deg + 1e-9);
    const Eigen::Vector3d down = p.rotation * Eigen::Vector3d::UnitY();
    const double roll = RadToDeg(std::atan2(-down.x(), down.y()));
    EXPECT_NEAR(roll, o.roll_deg, o.roll_amplitude_deg + 0.05);
    // Speed within ±5 % (finite differences).
    const double v = (tr.StationAt(t + 1e-4) - tr.StationAt(t - 1e-4)) / 2e-4;
    EXPECT_NEAR(v, 100.0, 5.0 + 1e-6);
  }
}

TEST(CapturePlan, RateFollowsTheOverlapAndTripletsAreSpaced) {
  Scenario s = PresetScenario("tiny");
  DefaultModuleOptions small;
  small.camera_width = s.camera_width;
  small.camera_height = s.camera_width * 3 / 4;
  const Rig rig = MakeRig(MakeDefaultModule(small), s.rig);
  const PipeGeometry pipe(s.world);
  const Trajectory tr(pipe, s.motion, s.seed);
  const CapturePlan plan = PlanCaptures(rig, tr, s.capture);
  EXPECT_GT(plan.footprint_mm, 120.0);  // ~170 mm at 150 mm from the axis
  EXPECT_LT(plan.footprint_mm, 220.0);
  EXPECT_NEAR(plan.period_s, 0.4 * plan.footprint_mm / 100.0, 1e-12);
  EXPECT_EQ(plan.acquisitions, static_cast<int>(std::floor(tr.DurationS() / plan.period_s)) + 1);
  ASSERT_EQ(plan.shots.size(), plan.acquisitions * 6u * 3u);
  for (size_t i = 1; i < plan.shots.size(); ++i)
    EXPECT_LE(plan.shots[i - 1].time_s, plan.shots[i].time_s);
  for (const RunImage& shot : plan.shots) {
    const double t0 = shot.counter * plan.period_s + (shot.module % 2) * 0.020;
    EXPECT_NEAR(shot.time_s, t0 + static_cast<int>(shot.kind) * 0.005, 1e-12);
  }
}

TEST(Odometry, DiffersFromTheTruthExactlyByTheErrorModel) {
  PipeWorld w;
  w.sections = {{.length_mm = 8000.0, .diameter_mm = 300.0}};
  const PipeGeometry pipe(w);
  MotionOptions m;
  m.travel_mm = 5000.0;
  const Trajectory tr(pipe, m, 3);
  OdometryOptions o;
  o.scale_error = 0.004;
  o.noise_mm = 0.5;
  o.slips = {{.station_mm = 1300.0, .length_mm = 400.0, .fraction = 0.25}};
  const auto samples = SimulateOdometry(tr, o, 11);
  ASSERT_GT(samples.size(), 900u);
  double sum = 0.0, sum2 = 0.0;
  for (const OdometrySample& s : samples) {
    EXPECT_NEAR(s.true_mm, tr.StationAt(s.time_s) - m.start_station_mm, 1e-9);
    EXPECT_NEAR(s.scale_mm, 0.004 * s.true_mm, 1e-9);
    const double station = tr.StationAt(s.time_s);
    const double expected_slip = -0.25 * std::clamp(station - 1300.0, 0.0, 400.0);
    EXPECT_NEAR(s.slip_mm, expected_slip, 1e-9);
    EXPECT_NEAR(s.measured_mm, s.true_mm + s.scale_mm + s.slip_mm + s.noise_mm, 1e-9);
    sum += s.noise_mm;
    sum2 += s.noise_mm * s.noise_mm;
  }
  const double n = static_cast<double>(samples.size());
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 4.0 * 0.5 / std::sqrt(n));
  EXPECT_NEAR(sd, 0.5, 0.5 * 5.0 / std::sqrt(2.0 * n));
  // At the end: 20 mm scale error and 100 mm swallowed by the slip.
  EXPECT_NEAR(samples.back().measured_mm - samples.back().true_mm,
              0.004 * samples.back().true_mm - 100.0, 2.5);
}

}  // namespace
}  // namespace sewer3d
