// Scenario files and the run files: round trips and one-line errors naming file and field.

#include "sewer3d/simio/scenario_io.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/simio/truth_io.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

std::string ErrorOf(const std::string& json) {
  try {
    ParseScenario(json, "scenario.json");
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

TEST(ScenarioIo, PresetsRoundTrip) {
  for (const std::string& name : PresetNames()) {
    const Scenario s = PresetScenario(name);
    const std::string text = ScenarioToJson(s);
    const Scenario back = ParseScenario(text, name + ".json");
    EXPECT_EQ(ScenarioToJson(back), text) << name;
    EXPECT_EQ(back.world.sections.size(), s.world.sections.size());
    EXPECT_EQ(back.world.features.size(), s.world.features.size());
    EXPECT_EQ(back.odometry.slips.size(), s.odometry.slips.size());
  }
}

TEST(ScenarioIo, TextureRealismMembersRoundTripAndDefault) {
  Scenario s = PresetScenario("tiny");
  s.truth_albedo = false;
  s.white_balance_error = 0.07;
  s.render.ring_light_exponent = 3.0;
  s.render.ring_light_color_shift = -0.05;
  s.render.color_shading = {1.0, 0.5, 0.0};
  s.render.sensor.color_filter = ColorFilter::kRggb;
  const Scenario back = ParseScenario(ScenarioToJson(s), "s.json");
  EXPECT_FALSE(back.truth_albedo);
  EXPECT_DOUBLE_EQ(back.white_balance_error, 0.07);
  EXPECT_DOUBLE_EQ(back.render.ring_light_exponent, 3.0);
  EXPECT_DOUBLE_EQ(back.render.ring_light_color_shift, -0.05);
  EXPECT_EQ(back.render.color_shading, Eigen::Vector3d(1.0, 0.5, 0.0));
  EXPECT_EQ(back.render.sensor.color_filter, ColorFilter::kRggb);
  EXPECT_EQ(PresetScenario("demo").render.sensor.color_filter, ColorFilter::kRggb);
  EXPECT_EQ(PresetScenario("long").render.sensor.color_filter, ColorFilter::kRggb);
  EXPECT_FALSE(PresetScenario("long").truth_albedo);
  EXPECT_TRUE(PresetScenario("demo").truth_albedo);
  // A file from before these members: the defaults.
  const Scenario old = ParseScenario(
      R"({"pipe": {"sections": [{"length_mm": 2000}]}, "render": {"supersampling": 2}})", "o.json");
  const RenderOptions defaults;
  EXPECT_FALSE(old.truth_albedo);
  EXPECT_DOUBLE_EQ(old.white_balance_error, Scenario().white_balance_error);
  EXPECT_EQ(old.render.sensor.color_filter, ColorFilter::kNone);
  EXPECT_EQ(old.render.color_shading, defaults.color_shading);
  EXPECT_DOUBLE_EQ(old.render.ring_light_color_shift, defaults.ring_light_color_shift);
  EXPECT_NE(ErrorOf(R"({"pipe": {"sections": [{"length_mm": 2000}]},
                        "render": {"color_filter": "BGGR"}})")
                .find("render.color_filter"),
            std::string::npos);
}

TEST(ScenarioIo, DefaultsFillAMinimalFile) {
  const Scenario s = ParseScenario(R"({"pipe": {"sections": [{"length_mm": 2000}]}})", "min.json");
  EXPECT_EQ(s.name, "min");
  EXPECT_EQ(s.rig.modules, 6);
  EXPECT_DOUBLE_EQ(s.world.sections[0].diameter_mm, 300.0);
  EXPECT_DOUBLE_EQ(s.motion.speed_mm_s, 100.0);
  EXPECT_DOUBLE_EQ(s.capture.nominal_diameter_mm, 300.0);
}

TEST(ScenarioIo, ErrorsNameTheFileAndTheField) {
  EXPECT_NE(ErrorOf(R"({"pipe": {"sections": [{"length_mm": 2000}]}, "motoin": {}})")
                .find("'motoin' is not a known field"),
            std::string::npos);
  EXPECT_NE(ErrorOf(R"({"pipe": {"sections": [{"lenght_mm": 2000}]}})")
                .find("pipe.sections[0].lenght_mm"),
            std::string::npos);
  EXPECT_NE(ErrorOf(R"({"pipe": {"sections": [{"length_mm": "long"}]}})")
                .find("pipe.sections[0].length_mm"),
            std::string::npos);
  EXPECT_NE(ErrorOf(R"({"pipe": {"sections": [{}], "features": [{"type": "root"}]}})").find("root"),
            std::string::npos);
  EXPECT_NE(ErrorOf(R"({"motion": {}})").find("'pipe' is missing"), std::string::npos);
  EXPECT_NE(ErrorOf(R"({"pipe": {"sections": [{"diameter_mm": 160}]}})").find("does not fit"),
            std::string::npos);
  EXPECT_NE(ErrorOf(R"({"pipe": )").find("invalid JSON"), std::string::npos);
  EXPECT_NE(ErrorOf(R"({"pipe": {"sections": [{}]}, "module": "m.json", "camera_width": 1296})")
                .find("field 'camera_width' sizes the built-in module only"),
            std::string::npos);
  EXPECT_EQ(
      ErrorOf(R"({"pipe": {"sections": [{}]}, "truth_depth": "some"})").rfind("scenario.json: ", 0),
      0u);
}

TEST(TruthIo, PosesRoundTrip) {
  const fs::path dir = fs::temp_directory_path() / "sewer3d_truth_io_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  TruthPose pose{
      1,
      2,
      ImageKind::kPattern,
      0.5,
      350.0,
      Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized())),
              Eigen::Vector3d(1.5, -2.25, 350.125))};
  WriteTruthPoses(dir / "poses.csv", {pose});
  const auto poses = ReadTruthPoses(dir / "poses.csv");
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_EQ(poses[0].kind, ImageKind::kPattern);
  EXPECT_DOUBLE_EQ(poses[0].station_mm, 350.0);
  EXPECT_NEAR(
      (poses[0].world_from_carrier.translation - pose.world_from_carrier.translation).norm(), 0.0,
      1e-6);
  EXPECT_LT(poses[0].world_from_carrier.rotation.angularDistance(pose.world_from_carrier.rotation),
            1e-11);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sewer3d
