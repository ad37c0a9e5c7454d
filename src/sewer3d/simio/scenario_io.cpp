#include "sewer3d/simio/scenario_io.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

#include "sewer3d/io/json_reader.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/simio/render_json.hpp"

namespace sewer3d {
namespace {

using nlohmann::json;

const char* TruthDepthName(TruthDepth t) {
  switch (t) {
    case TruthDepth::kAll:
      return "all";
    case TruthDepth::kPattern:
      return "pattern";
    case TruthDepth::kNone:
      return "none";
  }
  return "pattern";
}

// Render options the run sets for every shot, and the scenario member that gives each: not
// written into a scenario's render, refused there.
struct PerShotMember {
  const char* key;
  const char* given_as;
};
constexpr PerShotMember kPerShotMembers[] = {
    {"speed_mm_s", "motion.speed_mm_s"},
    {"exposure_ms", "capture.exposure_ms"},
    {"motion_direction", "the motion along the pipe (motion)"},
    {"white_balance", "white_balance_error"},
    {"truth_albedo", "truth_albedo"}};

json WorldJson(const PipeWorld& w) {
  json j;
  j["material_seed"] = w.material_seed;
  j["sections"] = json::array();
  for (const PipeSection& s : w.sections) {
    j["sections"].push_back({{"length_mm", s.length_mm},
                             {"diameter_mm", s.diameter_mm},
                             {"material", MaterialName(s.material)},
                             {"ovality_pct", s.ovality_pct},
                             {"ovality_clock_h", s.ovality_clock_h},
                             {"bend_radius_mm", s.bend_radius_mm},
                             {"bend_clock_h", s.bend_clock_h}});
  }
  j["joints"] = json::array();
  for (const PipeJoint& t : w.joints) {
    j["joints"].push_back({{"id", t.id},
                           {"gap_mm", t.gap_mm},
                           {"gap_depth_mm", t.gap_depth_mm},
                           {"offset_mm", t.offset_mm},
                           {"offset_clock_h", t.offset_clock_h},
                           {"deflection_deg", t.deflection_deg},
                           {"deflection_clock_h", t.deflection_clock_h}});
  }
  j["features"] = json::array();
  for (const PipeFeature& f : w.features) {
    json o{{"id", f.id},
           {"type", PipeFeatureTypeName(f.type)},
           {"station_mm", f.station_mm},
           {"clock_h", f.clock_h}};
    switch (f.type) {
      case PipeFeature::Type::kConnection:
        o.update({{"diameter_mm", f.diameter_mm},
                  {"wall_mm", f.wall_mm},
                  {"intrusion_mm", f.intrusion_mm}});
        break;
      case PipeFeature::Type::kSpalling:
        o.update({{"length_mm", f.length_mm}, {"width_mm", f.width_mm}, {"depth_mm", f.depth_mm}});
        break;
      case PipeFeature::Type::kWet:
        o.update({{"length_mm", f.length_mm}, {"width_mm", f.width_mm}});
        break;
      case PipeFeature::Type::kCrack:
        o.update({{"length_mm", f.length_mm},
                  {"width_mm", f.width_mm},
                  {"depth_mm", f.depth_mm},
                  {"angle_deg", f.angle_deg}});
        break;
      case PipeFeature::Type::kDeposit:
        o.update({{"length_mm", f.length_mm}, {"height_mm", f.height_mm}});
        break;
      case PipeFeature::Type::kBump:
      case PipeFeature::Type::kPit:
      case PipeFeature::Type::kJointStep:
        break;  // pipe-wall scene kinds, which PipeWorld::Check keeps out of a pipe world
    }
    j["features"].push_back(o);
  }
  return j;
}

PipeWorld ReadWorld(const JsonReader& in, const json& j) {
  in.OnlyKnown(j, "pipe.", {"material_seed", "sections", "joints", "features"});
  PipeWorld w;
  w.material_seed = in.Seed(j, "material_seed", "pipe.", 1);
  const json& sections = in.Array(j, "sections", "pipe.");
  for (size_t i = 0; i < sections.size(); ++i) {
    const std::string p = "pipe.sections[" + std::to_string(i) + "].";
    const json& o = sections[i];
    if (!o.is_object()) in.Fail(p, "must be an object");
    in.OnlyKnown(o, p,
                 {"length_mm", "diameter_mm", "material", "ovality_pct", "ovality_clock_h",
                  "bend_radius_mm", "bend_clock_h"});
    PipeSection s;
    s.length_mm = in.Number(o, "length_mm", p, s.length_mm);
    s.diameter_mm = in.Number(o, "diameter_mm", p, s.diameter_mm);
    s.material = ParseMaterial(in, in.Text(o, "material", p, "concrete"), p + "material");
    s.ovality_pct = in.Number(o, "ovality_pct", p, s.ovality_pct);
    s.ovality_clock_h = in.Number(o, "ovality_clock_h", p, s.ovality_clock_h);
    s.bend_radius_mm = in.Number(o, "bend_radius_mm", p, s.bend_radius_mm);
    s.bend_clock_h = in.Number(o, "bend_clock_h", p, s.bend_clock_h);
    w.sections.push_back(s);
  }
  const json& joints = in.Array(j, "joints", "pipe.");
  for (size_t i = 0; i < joints.size(); ++i) {
    const std::string p = "pipe.joints[" + std::to_string(i) + "].";
    const json& o = joints[i];
    if (!o.is_object()) in.Fail(p, "must be an object");
    in.OnlyKnown(o, p,
                 {"id", "gap_mm", "gap_depth_mm", "offset_mm", "offset_clock_h", "deflection_deg",
                  "deflection_clock_h"});
    PipeJoint t;
    t.id = in.Text(o, "id", p, fmt::format("J{}", i + 1));
    if (t.id.empty()) in.Fail(p + "id", "must not be empty (truth files name joints by id)");
    t.gap_mm = in.Number(o, "gap_mm", p, t.gap_mm);
    t.gap_depth_mm = in.Number(o, "gap_depth_mm", p, t.gap_depth_mm);
    t.offset_mm = in.Number(o, "offset_mm", p, t.offset_mm);
    t.offset_clock_h = in.Number(o, "offset_clock_h", p, t.offset_clock_h);
    t.deflection_deg = in.Number(o, "deflection_deg", p, t.deflection_deg);
    t.deflection_clock_h = in.Number(o, "deflection_clock_h", p, t.deflection_clock_h);
    w.joints.push_back(t);
  }
  const json& features = in.Array(j, "features", "pipe.");
  for (size_t i = 0; i < features.size(); ++i) {
    const std::string p = "pipe.features[" + std::to_string(i) + "].";
    const json& o = features[i];
    if (!o.is_object()) in.Fail(p, "must be an object");
    in.OnlyKnown(o, p,
                 {"id", "type", "station_mm", "clock_h", "diameter_mm", "wall_mm", "intrusion_mm",
                  "length_mm", "width_mm", "depth_mm", "height_mm", "angle_deg"});
    PipeFeature f;
    const std::string type = in.Text(o, "type", p, "");
    const auto kind = PipeFeatureTypeFromName(type);
    if (!kind)
      in.Fail(p + "type",
              "must be connection, spalling, crack, deposit or wet, got '" + type + "'");
    f.type = *kind;  // PipeWorld::Check rejects the kinds only a pipe-wall scene takes
    f.id = in.Text(o, "id", p, fmt::format("F{}", i + 1));
    if (f.id.empty()) in.Fail(p + "id", "must not be empty (truth files name features by id)");
    f.station_mm = in.Number(o, "station_mm", p, f.station_mm);
    f.clock_h = in.Number(o, "clock_h", p, f.type == PipeFeature::Type::kDeposit ? 6.0 : f.clock_h);
    f.diameter_mm = in.Number(o, "diameter_mm", p, 0.0);
    f.wall_mm = in.Number(o, "wall_mm", p, f.type == PipeFeature::Type::kConnection ? 12.0 : 0.0);
    f.intrusion_mm = in.Number(o, "intrusion_mm", p, 0.0);
    f.length_mm = in.Number(o, "length_mm", p, 0.0);
    f.width_mm = in.Number(o, "width_mm", p, 0.0);
    f.depth_mm = in.Number(o, "depth_mm", p, 0.0);
    f.height_mm = in.Number(o, "height_mm", p, 0.0);
    f.angle_deg = in.Number(o, "angle_deg", p, 0.0);
    w.features.push_back(f);
  }
  return w;
}

}  // namespace

std::string PipeWorldToJson(const PipeWorld& world) { return WorldJson(world).dump(2); }

std::string ScenarioToJson(const Scenario& s) {
  json j;
  j["name"] = s.name;
  j["seed"] = s.seed;
  if (s.module_file.empty())
    j["camera_width"] = s.camera_width;  // sizes the built-in module only
  else
    j["module"] = s.module_file;
  j["rig"] = {{"modules", s.rig.modules},
              {"first_clock_h", s.rig.first_clock_h},
              {"stagger_mm", s.rig.stagger_mm},
              {"carrier_diameter_mm", s.rig.carrier_diameter_mm},
              {"carrier_length_mm", s.rig.carrier_length_mm}};
  j["pipe"] = WorldJson(s.world);
  const MotionOptions& m = s.motion;
  j["motion"] = {{"speed_mm_s", m.speed_mm_s},
                 {"speed_variation", m.speed_variation},
                 {"start_station_mm", m.start_station_mm},
                 {"travel_mm", m.travel_mm},
                 {"offset_mm", {m.offset_mm.x(), m.offset_mm.y()}},
                 {"wander_mm", m.wander_mm},
                 {"roll_deg", m.roll_deg},
                 {"roll_amplitude_deg", m.roll_amplitude_deg},
                 {"wobble_deg", m.wobble_deg}};
  const CaptureOptions& c = s.capture;
  j["capture"] = {{"overlap", c.overlap},
                  {"triplet_interval_ms", c.triplet_interval_ms},
                  {"group_delay_ms", c.group_delay_ms},
                  {"exposure_ms", c.exposure_ms},
                  {"nominal_diameter_mm", c.nominal_diameter_mm}};
  j["odometry"] = {{"rate_hz", s.odometry.rate_hz},
                   {"scale_error", s.odometry.scale_error},
                   {"noise_mm", s.odometry.noise_mm},
                   {"slips", json::array()}};
  for (const OdometrySlip& slip : s.odometry.slips) {
    j["odometry"]["slips"].push_back({{"station_mm", slip.station_mm},
                                      {"length_mm", slip.length_mm},
                                      {"fraction", slip.fraction}});
  }
  j["inclinometer"] = {{"enabled", s.inclinometer.enabled},
                       {"rate_hz", s.inclinometer.rate_hz},
                       {"noise_deg", s.inclinometer.noise_deg},
                       {"mounting_deg", s.inclinometer.mounting_deg}};
  json render = RenderOptionsToJson(s.render);
  for (const PerShotMember& m : kPerShotMembers) render.erase(m.key);
  j["render"] = render;
  j["truth_depth"] = TruthDepthName(s.truth_depth);
  j["truth_albedo"] = s.truth_albedo;
  j["white_balance_error"] = s.white_balance_error;
  return j.dump(2);
}

Scenario ParseScenario(const std::string& text, const std::filesystem::path& path) {
  const JsonReader in(path);
  const json j = in.ParseObject(text);
  in.OnlyKnown(
      j, "",
      {"name", "seed", "module", "camera_width", "rig", "pipe", "motion", "capture", "odometry",
       "inclinometer", "render", "truth_depth", "truth_albedo", "white_balance_error"});
  Scenario s;
  s.name = in.Text(j, "name", "", path.stem().string());
  s.seed = in.Seed(j, "seed", "", 1);
  s.module_file = in.Text(j, "module", "", "");
  s.camera_width = in.Integer(j, "camera_width", "", s.camera_width);
  if (j.contains("module") && j.contains("camera_width")) {
    in.Fail("camera_width", "sizes the built-in module only: the module file \"" + s.module_file +
                                "\" has its own camera; remove one of the two");
  }
  const json& rig = in.Object(j, "rig", "");
  in.OnlyKnown(
      rig, "rig.",
      {"modules", "first_clock_h", "stagger_mm", "carrier_diameter_mm", "carrier_length_mm"});
  s.rig.modules = in.Integer(rig, "modules", "rig.", s.rig.modules);
  s.rig.first_clock_h = in.Number(rig, "first_clock_h", "rig.", s.rig.first_clock_h);
  s.rig.stagger_mm = in.Number(rig, "stagger_mm", "rig.", s.rig.stagger_mm);
  s.rig.carrier_diameter_mm =
      in.Number(rig, "carrier_diameter_mm", "rig.", s.rig.carrier_diameter_mm);
  s.rig.carrier_length_mm = in.Number(rig, "carrier_length_mm", "rig.", s.rig.carrier_length_mm);
  if (!j.contains("pipe")) in.Fail("pipe", "is missing");
  s.world = ReadWorld(in, in.Object(j, "pipe", ""));
  const json& m = in.Object(j, "motion", "");
  in.OnlyKnown(m, "motion.",
               {"speed_mm_s", "speed_variation", "start_station_mm", "travel_mm", "offset_mm",
                "wander_mm", "roll_deg", "roll_amplitude_deg", "wobble_deg"});
  MotionOptions& mo = s.motion;
  mo.speed_mm_s = in.Number(m, "speed_mm_s", "motion.", mo.speed_mm_s);
  mo.speed_variation = in.Number(m, "speed_variation", "motion.", mo.speed_variation);
  mo.start_station_mm = in.Number(m, "start_station_mm", "motion.", mo.start_station_mm);
  mo.travel_mm = in.Number(m, "travel_mm", "motion.", mo.travel_mm);
  if (const auto it = m.find("offset_mm"); it != m.end()) {
    if (!it->is_array() || it->size() != 2 || !(*it)[0].is_number() || !(*it)[1].is_number()) {
      in.Fail("motion.offset_mm", "must be an array of 2 numbers (x right, y down)");
    }
    mo.offset_mm = {(*it)[0].get<double>(), (*it)[1].get<double>()};
  }
  mo.wander_mm = in.Number(m, "wander_mm", "motion.", mo.wander_mm);
  mo.roll_deg = in.Number(m, "roll_deg", "motion.", mo.roll_deg);
  mo.roll_amplitude_deg = in.Number(m, "roll_amplitude_deg", "motion.", mo.roll_amplitude_deg);
  mo.wobble_deg = in.Number(m, "wobble_deg", "motion.", mo.wobble_deg);
  const json& c = in.Object(j, "capture", "");
  in.OnlyKnown(
      c, "capture.",
      {"overlap", "triplet_interval_ms", "group_delay_ms", "exposure_ms", "nominal_diameter_mm"});
  s.capture.overlap = in.Number(c, "overlap", "capture.", s.capture.overlap);
  s.capture.triplet_interval_ms =
      in.Number(c, "triplet_interval_ms", "capture.", s.capture.triplet_interval_ms);
  s.capture.group_delay_ms = in.Number(c, "group_delay_ms", "capture.", s.capture.group_delay_ms);
  s.capture.exposure_ms = in.Number(c, "exposure_ms", "capture.", s.capture.exposure_ms);
  s.capture.nominal_diameter_mm =
      in.Number(c, "nominal_diameter_mm", "capture.",
                s.world.sections.empty() ? 300.0 : s.world.sections[0].diameter_mm);
  const json& o = in.Object(j, "odometry", "");
  in.OnlyKnown(o, "odometry.", {"rate_hz", "scale_error", "noise_mm", "slips"});
  s.odometry.rate_hz = in.Number(o, "rate_hz", "odometry.", s.odometry.rate_hz);
  s.odometry.scale_error = in.Number(o, "scale_error", "odometry.", s.odometry.scale_error);
  s.odometry.noise_mm = in.Number(o, "noise_mm", "odometry.", s.odometry.noise_mm);
  const json& slips = in.Array(o, "slips", "odometry.");
  for (size_t i = 0; i < slips.size(); ++i) {
    const std::string p = "odometry.slips[" + std::to_string(i) + "].";
    if (!slips[i].is_object()) in.Fail(p, "must be an object");
    in.OnlyKnown(slips[i], p, {"station_mm", "length_mm", "fraction"});
    s.odometry.slips.push_back({in.Number(slips[i], "station_mm", p, 0.0),
                                in.Number(slips[i], "length_mm", p, 0.0),
                                in.Number(slips[i], "fraction", p, 0.0)});
  }
  const json& incl = in.Object(j, "inclinometer", "");
  in.OnlyKnown(incl, "inclinometer.", {"enabled", "rate_hz", "noise_deg", "mounting_deg"});
  InclinometerOptions& io = s.inclinometer;
  io.enabled = in.Bool(incl, "enabled", "inclinometer.", io.enabled);
  io.rate_hz = in.Number(incl, "rate_hz", "inclinometer.", io.rate_hz);
  io.noise_deg = in.Number(incl, "noise_deg", "inclinometer.", io.noise_deg);
  io.mounting_deg = in.Number(incl, "mounting_deg", "inclinometer.", io.mounting_deg);
  const json& render = in.Object(j, "render", "");
  // What the run sets per shot is the scenario's to give, not the renderer's.
  for (const PerShotMember& m : kPerShotMembers) {
    if (render.contains(m.key))
      in.Fail(std::string("render.") + m.key,
              std::string("is set by the run for every shot; give it as ") + m.given_as);
  }
  ReadRenderOptions(in, render, "render.", s.render);
  s.truth_albedo = in.Bool(j, "truth_albedo", "", s.truth_albedo);
  s.white_balance_error = in.Number(j, "white_balance_error", "", s.white_balance_error);
  const std::string truth = in.Text(j, "truth_depth", "", "pattern");
  if (truth == "all")
    s.truth_depth = TruthDepth::kAll;
  else if (truth == "pattern")
    s.truth_depth = TruthDepth::kPattern;
  else if (truth == "none")
    s.truth_depth = TruthDepth::kNone;
  else
    in.Fail("truth_depth", "must be all, pattern or none, got '" + truth + "'");
  ValidateFileContents(path, [&] { s.Check(); });
  return s;
}

Scenario ReadScenario(const std::filesystem::path& path) {
  return ParseScenario(ReadTextFile(path), path);
}

std::string ModuleFileFromTruth(const std::filesystem::path& run_folder,
                                const std::filesystem::path& module_file) {
  std::error_code ec;
  const std::filesystem::path truth = std::filesystem::absolute(run_folder) / "truth";
  const std::filesystem::path absolute = std::filesystem::absolute(module_file);
  const std::filesystem::path relative = std::filesystem::relative(absolute, truth, ec);
  return (ec || relative.empty() ? absolute : relative).generic_string();
}

}  // namespace sewer3d
