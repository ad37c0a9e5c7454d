// Scenario files and the run files: round trips and one-line errors naming file and field.

#include "sewer3d/io/scenario_io.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/pattern/default_pattern.hpp"

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
  EXPECT_EQ(
      ErrorOf(R"({"pipe": {"sections": [{}]}, "truth_depth": "some"})").rfind("scenario.json: ", 0),
      0u);
}

TEST(RunIo, RigIndexAndPosesRoundTrip) {
  const fs::path dir = fs::temp_directory_path() / "sewer3d_run_io_test";
  fs::remove_all(dir);
  DefaultModuleOptions o;
  o.camera_width = 648;
  o.camera_height = 486;
  const Rig rig = MakeRig(MakeDefaultModule(o), {});
  WriteRig(dir / "rig.json", rig);
  WritePatternMatrix(dir / "pattern.png", DefaultPatternArray());
  const LoadedRig back = ReadRig(dir / "rig.json");
  ASSERT_EQ(back.rig.modules.size(), 6u);
  for (size_t k = 0; k < 6; ++k) {
    const RigModule &a = rig.modules[k], &b = back.rig.modules[k];
    EXPECT_EQ(a.name, b.name);
    EXPECT_NEAR((a.carrier_from_camera.translation - b.carrier_from_camera.translation).norm(), 0.0,
                1e-9);
    EXPECT_LT(a.carrier_from_camera.rotation.angularDistance(b.carrier_from_camera.rotation), 1e-9);
    EXPECT_DOUBLE_EQ(a.module.camera.fx, b.module.camera.fx);
    EXPECT_EQ(back.patterns[k].rows, DefaultPatternArray().rows);
  }
  const std::vector<IndexEntry> index{
      {3, 7, ImageKind::kTextureAfter, 1.234567, 2.0, "images/m3/000007_texture_after.png"}};
  WriteIndex(dir / "acquisitions.csv", index);
  const auto index_back = ReadIndex(dir / "acquisitions.csv");
  ASSERT_EQ(index_back.size(), 1u);
  EXPECT_EQ(index_back[0].kind, ImageKind::kTextureAfter);
  EXPECT_EQ(index_back[0].file, index[0].file);
  EXPECT_DOUBLE_EQ(index_back[0].time_s, 1.234567);
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
  EXPECT_NEAR(
      (poses[0].world_from_carrier.translation - pose.world_from_carrier.translation).norm(), 0.0,
      1e-6);
  EXPECT_LT(poses[0].world_from_carrier.rotation.angularDistance(pose.world_from_carrier.rotation),
            1e-11);
  // A malformed line is named.
  std::ofstream(dir / "bad.csv")
      << "module,counter,image,time_s,exposure_ms,file\n0,0,pattern,abc,2,x.png\n";
  try {
    ReadIndex(dir / "bad.csv");
    FAIL() << "no error";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sewer3d
