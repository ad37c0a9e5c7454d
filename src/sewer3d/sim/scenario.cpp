#include "sewer3d/sim/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "sewer3d/core/check.hpp"
#include "sewer3d/sim/material.hpp"

namespace sewer3d {
namespace {

PipeJoint Joint(const std::string& id, double gap, double depth, double offset, double offset_clock,
                double deflection = 0.0, double deflection_clock = 3.0) {
  PipeJoint j;
  j.id = id;
  j.gap_mm = gap;
  j.gap_depth_mm = depth;
  j.offset_mm = offset;
  j.offset_clock_h = offset_clock;
  j.deflection_deg = deflection;
  j.deflection_clock_h = deflection_clock;
  return j;
}

using Feature = PipeFeature::Type;

Scenario Tiny() {
  Scenario s;
  s.name = "tiny";
  s.camera_width = 648;
  s.world.sections = {{.length_mm = 400.0, .diameter_mm = 300.0},
                      {.length_mm = 600.0, .diameter_mm = 300.0}};
  s.world.joints = {Joint("J1", 8.0, 5.0, 4.0, 12.0)};
  s.world.features = {{.type = Feature::kConnection,
                       .id = "C1",
                       .station_mm = 300.0,
                       .clock_h = 2.0,
                       .diameter_mm = 100.0,
                       .wall_mm = 12.0,
                       .intrusion_mm = 15.0},
                      {.type = Feature::kCrack,
                       .id = "K1",
                       .station_mm = 250.0,
                       .clock_h = 8.0,
                       .length_mm = 80.0,
                       .width_mm = 1.5,
                       .depth_mm = 3.0,
                       .angle_deg = 30.0}};
  s.motion.start_station_mm = 350.0;
  s.motion.travel_mm = 100.0;
  s.render.supersampling = 1;
  // The tests' run: without the paper profile's error sources, so that their tolerances
  // measure the stages and the renderer's truth is the wall seen by the module file's camera.
  s.render.spot_errors = SpotErrors{};
  s.truth_depth = TruthDepth::kAll;
  s.truth_albedo = true;
  return s;
}

Scenario Demo() {
  Scenario s;
  s.name = "demo";
  s.world.sections = {{.length_mm = 700.0, .diameter_mm = 300.0},
                      {.length_mm = 400.0, .diameter_mm = 300.0},
                      {.length_mm = 1000.0, .diameter_mm = 300.0, .material = Material::kPlastic}};
  s.world.joints = {Joint("J1", 10.0, 6.0, 6.0, 1.0, 1.0, 3.0), Joint("J2", 4.0, 3.0, 1.0, 6.0)};
  s.world.features = {{.type = Feature::kConnection,
                       .id = "C1",
                       .station_mm = 900.0,
                       .clock_h = 2.0,
                       .diameter_mm = 150.0,
                       .wall_mm = 12.0,
                       .intrusion_mm = 25.0},
                      {.type = Feature::kSpalling,
                       .id = "S1",
                       .station_mm = 1020.0,
                       .clock_h = 10.0,
                       .length_mm = 70.0,
                       .width_mm = 50.0,
                       .depth_mm = 6.0},
                      {.type = Feature::kCrack,
                       .id = "K1",
                       .station_mm = 450.0,
                       .clock_h = 4.5,
                       .length_mm = 120.0,
                       .width_mm = 1.2,
                       .depth_mm = 3.0,
                       .angle_deg = 20.0}};
  s.motion.start_station_mm = 300.0;
  s.motion.travel_mm = 1000.0;
  s.render.supersampling = 1;
  s.truth_depth = TruthDepth::kNone;  // 20 MB per full-size map; the world and poses define it
  s.render.sensor.color_filter = ColorFilter::kRggb;
  s.truth_albedo = true;
  return s;
}

// The demo preset's story in about half the travel at tiny's image size: what `sewer3d demo`
// runs in a few minutes on two cores. The modules are staggered over 450 mm along the carrier,
// so every module sees stations from start + 142 to end − 142 (372..622 mm here): the joint,
// the connection and the start of the plastic lie in that window.
Scenario Compact() {
  Scenario s;
  s.name = "compact";
  s.camera_width = 648;
  s.world.sections = {{.length_mm = 420.0, .diameter_mm = 300.0},
                      {.length_mm = 140.0, .diameter_mm = 300.0},
                      {.length_mm = 740.0, .diameter_mm = 300.0, .material = Material::kPlastic}};
  s.world.joints = {Joint("J1", 10.0, 6.0, 6.0, 1.0, 1.0, 3.0), Joint("J2", 4.0, 3.0, 1.0, 6.0)};
  s.world.features = {{.type = Feature::kConnection,
                       .id = "C1",
                       .station_mm = 490.0,
                       .clock_h = 2.0,
                       .diameter_mm = 100.0,
                       .wall_mm = 12.0,
                       .intrusion_mm = 15.0}};
  s.motion.start_station_mm = 230.0;
  s.motion.travel_mm = 560.0;
  s.render.supersampling = 1;
  s.truth_depth = TruthDepth::kNone;  // the evaluations use the world, poses and albedo
  s.render.sensor.color_filter = ColorFilter::kRggb;
  s.truth_albedo = true;
  return s;
}

Scenario Long() {
  Scenario s;
  s.name = "long";
  const PipeSection concrete{.length_mm = 2000.0, .diameter_mm = 300.0};
  const PipeSection clay{
      .length_mm = 1000.0, .diameter_mm = 300.0, .material = Material::kVitrifiedClay};
  PipeSection plastic{.length_mm = 3000.0, .diameter_mm = 300.0, .material = Material::kPlastic};
  PipeSection bent = concrete;
  bent.bend_radius_mm = 30000.0;
  bent.bend_clock_h = 3.0;
  PipeSection deformed = plastic;
  deformed.ovality_pct = 6.0;
  s.world.sections = {concrete, bent, clay, clay, clay, deformed, plastic};
  s.world.joints = {Joint("J1", 6.0, 4.0, 3.0, 12.0), Joint("J2", 12.0, 6.0, 8.0, 2.0, 1.5, 9.0),
                    Joint("J3", 5.0, 3.0, 2.0, 4.0),  Joint("J4", 5.0, 3.0, 0.0, 12.0, 2.0, 12.0),
                    Joint("J5", 8.0, 5.0, 5.0, 9.0),  Joint("J6", 3.0, 2.0, 0.0, 12.0)};
  s.world.features = {{.type = Feature::kConnection,
                       .id = "C1",
                       .station_mm = 1200.0,
                       .clock_h = 2.0,
                       .diameter_mm = 150.0,
                       .wall_mm = 12.0,
                       .intrusion_mm = 25.0},
                      {.type = Feature::kConnection,
                       .id = "C2",
                       .station_mm = 5600.0,
                       .clock_h = 10.0,
                       .diameter_mm = 100.0,
                       .wall_mm = 12.0,
                       .intrusion_mm = 10.0},
                      {.type = Feature::kSpalling,
                       .id = "S1",
                       .station_mm = 800.0,
                       .clock_h = 11.0,
                       .length_mm = 90.0,
                       .width_mm = 60.0,
                       .depth_mm = 8.0},
                      {.type = Feature::kSpalling,
                       .id = "S2",
                       .station_mm = 3300.0,
                       .clock_h = 5.0,
                       .length_mm = 40.0,
                       .width_mm = 40.0,
                       .depth_mm = 4.0},
                      {.type = Feature::kCrack,
                       .id = "K1",
                       .station_mm = 2500.0,
                       .clock_h = 1.0,
                       .length_mm = 300.0,
                       .width_mm = 1.0,
                       .depth_mm = 3.0},
                      {.type = Feature::kCrack,
                       .id = "K2",
                       .station_mm = 6200.0,
                       .clock_h = 8.0,
                       .length_mm = 150.0,
                       .width_mm = 2.0,
                       .depth_mm = 4.0,
                       .angle_deg = 90.0},
                      {.type = Feature::kDeposit,
                       .id = "D1",
                       .station_mm = 4200.0,
                       .clock_h = 6.0,
                       .length_mm = 900.0,
                       .height_mm = 30.0}};
  s.motion.start_station_mm = 300.0;
  s.motion.travel_mm = 10000.0;
  s.render.supersampling = 1;
  s.truth_depth = TruthDepth::kNone;
  s.render.sensor.color_filter = ColorFilter::kRggb;
  s.odometry.slips = {{.station_mm = 4300.0, .length_mm = 500.0, .fraction = 0.15}};
  return s;
}

}  // namespace

void Scenario::Check() const {
  // Field names as in scenario files (docs/formats.md).
  SEWER3D_VALIDATE(!name.empty(), "name", "must not be empty");
  SEWER3D_VALIDATE(camera_width >= 160 && camera_width <= 8192, "camera_width",
                   "must be 160..8192 px, got " << camera_width);
  CheckWithin("rig.", [&] { rig.Check(); });
  CheckWithin("pipe.", [&] { world.Check(); });
  CheckWithin("motion.", [&] { motion.Check(); });
  CheckWithin("capture.", [&] { capture.Check(); });
  // The capture is planned for this diameter; far from the pipe's, the planned overlap is not
  // the overlap the run gets.
  double smallest = 1e300, largest = 0.0;
  for (const PipeSection& section : world.sections) {
    smallest = std::min(smallest, section.diameter_mm);
    largest = std::max(largest, section.diameter_mm);
  }
  SEWER3D_VALIDATE(world.sections.empty() || (capture.nominal_diameter_mm >= 0.75 * smallest &&
                                              capture.nominal_diameter_mm <= 1.25 * largest),
                   "capture.nominal_diameter_mm",
                   "must lie within 25 % of the pipe's diameters (" << smallest << ".." << largest
                                                                    << " mm), got "
                                                                    << capture.nominal_diameter_mm);
  CheckWithin("odometry.", [&] { odometry.Check(); });
  CheckWithin("inclinometer.", [&] { inclinometer.Check(); });
  CheckWithin("render.", [&] { render.Check(); });
  // The frames are rendered with the carrier's speed over the capture's exposure.
  RenderOptions moving = render;
  moving.speed_mm_s = motion.speed_mm_s;
  moving.exposure_ms = capture.exposure_ms;
  CheckWithin("motion.", [&] { moving.Check(); });
  SEWER3D_VALIDATE(white_balance_error >= 0.0 && white_balance_error <= 0.5, "white_balance_error",
                   "must be 0..0.5, got " << white_balance_error);
  const double length = world.LengthMm();
  for (size_t i = 0; i < odometry.slips.size(); ++i) {
    const double s = odometry.slips[i].station_mm;
    SEWER3D_VALIDATE(s >= -length && s <= 2.0 * length,
                     "odometry.slips[" + std::to_string(i) + "].station_mm",
                     "lies far outside the " << length << " mm pipe, got " << s);
  }
  for (size_t i = 0; i < world.sections.size(); ++i) {
    const double diameter = world.sections[i].diameter_mm;
    SEWER3D_VALIDATE(
        motion.offset_mm.norm() + motion.wander_mm + 0.5 * rig.carrier_diameter_mm < 0.5 * diameter,
        "pipe.sections[" + std::to_string(i) + "].diameter_mm",
        "the carrier (Ø" << rig.carrier_diameter_mm << ", offset " << motion.offset_mm.norm()
                         << " mm, wander " << motion.wander_mm << " mm) does not fit in a Ø"
                         << diameter << " section");
  }
  // Each camera looks at the wall around its own module's station: beyond the pipe's ends the
  // simulator extends the end sections, a pipe nobody described. The outermost modules may stand
  // out by a radius (a robot entering from a manhole), not more.
  const double half_span = 0.5 * (rig.modules - 1) * rig.stagger_mm;
  const double rear = motion.start_station_mm - half_span;
  const double front = motion.start_station_mm + motion.travel_mm + half_span;
  const double start_margin = 0.5 * world.sections.front().diameter_mm;
  const double end_margin = 0.5 * world.sections.back().diameter_mm;
  SEWER3D_VALIDATE(rear >= -start_margin, "motion.start_station_mm",
                   "the rear module starts at station "
                       << rear << " mm, more than a radius (" << start_margin
                       << " mm) before the pipe's start; start at " << half_span - start_margin
                       << " mm or later");
  SEWER3D_VALIDATE(front <= length + end_margin, "motion.travel_mm",
                   "the front module would reach station "
                       << front << " mm, more than a radius (" << end_margin
                       << " mm) past the end of the " << length << " mm pipe (start_station_mm "
                       << motion.start_station_mm << " + travel_mm " << motion.travel_mm << " + "
                       << half_span << " mm to the front module)");
}

Eigen::Vector3d CameraWhiteBalance(const Scenario& scenario, int module) {
  const auto m = static_cast<std::uint64_t>(module);
  const double sigma = scenario.white_balance_error;
  return {std::exp(sigma * HashNormal(scenario.seed, 0x3b, m)), 1.0,
          std::exp(sigma * HashNormal(scenario.seed, 0xbb, m))};
}

RenderOptions RunRenderDefaults() {
  RenderOptions o;
  o.spot_errors = *RealismProfile("paper");
  return o;
}

const std::vector<std::string>& PresetNames() {
  static const std::vector<std::string> names{"tiny", "compact", "demo", "long"};
  return names;
}

Scenario PresetScenario(const std::string& name) {
  Scenario s;
  if (name == "tiny")
    s = Tiny();
  else if (name == "compact")
    s = Compact();
  else if (name == "demo")
    s = Demo();
  else if (name == "long")
    s = Long();
  else
    throw InvalidValue("preset", "must be tiny, compact, demo or long, got '" + name + "'");
  s.odometry.slips.push_back({.station_mm = s.motion.start_station_mm + 0.4 * s.motion.travel_mm,
                              .length_mm = 0.1 * s.motion.travel_mm,
                              .fraction = 0.2});
  s.Check();
  return s;
}

}  // namespace sewer3d
