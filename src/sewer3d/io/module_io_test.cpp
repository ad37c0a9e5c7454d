#include "sewer3d/io/module_io.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/io/calibration_io.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/pattern/default_pattern.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class ModuleIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("sewer3d_module_io_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    WritePatternMatrix(dir_ / "pattern.png", DefaultPatternArray());
    good_ = json::parse(ModuleToJson(MakeDefaultModule({})));
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path Write(const std::string& text, const std::string& name = "module.json") {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  // Expects LoadModule to throw a FileError whose one-line message names the file and `needle`.
  void ExpectError(const json& doc, const std::string& needle) {
    ExpectErrorText(doc.dump(), needle);
  }
  void ExpectErrorText(const std::string& text, const std::string& needle) {
    const fs::path path = Write(text);
    try {
      LoadModule(path);
      ADD_FAILURE() << "no error for " << needle;
    } catch (const FileError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path.string()), std::string::npos) << what;
      EXPECT_NE(what.find(needle), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }

  fs::path dir_;
  json good_;
};

TEST_F(ModuleIoTest, RoundTripKeepsValuesAndUnknownFields) {
  json doc = good_;
  doc["serial"] = "SL-0042";
  doc["camera"]["sensor"] = {{"model", "IMX"}, {"bits", 12}};
  doc["pattern"]["wavelength_nm"] = 850;
  const LoadedModule loaded = LoadModule(Write(doc.dump(2)));
  EXPECT_EQ(loaded.pattern, DefaultPatternArray());
  const ModuleDescription original = MakeDefaultModule({});
  EXPECT_DOUBLE_EQ(loaded.module.camera.fx, original.camera.fx);
  EXPECT_DOUBLE_EQ(loaded.module.projector.cx, original.projector.cx);
  EXPECT_LT(
      (loaded.module.projector_from_camera.translation - original.projector_from_camera.translation)
          .norm(),
      1e-12);

  SaveModule(dir_ / "rewritten.json", loaded.module);
  const LoadedModule again = LoadModule(dir_ / "rewritten.json");
  EXPECT_DOUBLE_EQ(again.module.camera.k[0], original.camera.k[0]);
  EXPECT_LT(again.module.projector_from_camera.rotation.angularDistance(
                original.projector_from_camera.rotation),
            1e-12);
  std::ifstream in(dir_ / "rewritten.json");
  const json rewritten = json::parse(in);
  EXPECT_EQ(rewritten["serial"], "SL-0042");
  EXPECT_EQ(rewritten["camera"]["sensor"]["bits"], 12);
  EXPECT_EQ(rewritten["pattern"]["wavelength_nm"], 850);
}

TEST_F(ModuleIoTest, RefusesANameOneOrTwoEditsFromAKnownOne) {
  json d = good_;
  d["pattern"]["offset_pxx"] = {1.0, 2.0};
  ExpectError(d,
              "'pattern.offset_pxx' is not a field sewer3d reads; did you mean "
              "'pattern.offset_px'?");
  d = good_;
  d["Camera"] = d["camera"];
  ExpectError(d, "did you mean 'camera'?");
}

TEST_F(ModuleIoTest, RejectsBadFieldsWithOneLineNamingTheField) {
  json d = good_;
  d["camera"].erase("fx");
  ExpectError(d, "'camera.fx' is missing");
  d = good_;
  d["camera"]["fx"] = "1200";
  ExpectError(d, "'camera.fx' must be a number");
  d = good_;
  d["projector"]["fy"] = -5.0;
  ExpectError(d, "'projector.fy' must be positive");
  d = good_;
  d["camera"]["width"] = 0;
  ExpectError(d, "'camera.width' must be a positive size");
  d = good_;
  d["camera"]["height"] = 19.5;
  ExpectError(d, "'camera.height' must be an integer");
  d = good_;
  d["camera"]["k"] = {0.1, 0.2};
  ExpectError(d, "'camera.k' must be an array of 3");
  d = good_;
  d["projector_from_camera"]["rotation"] = {1, 0, 0, 0, 1, 0, 0, 0.3, 1};
  ExpectError(d, "'projector_from_camera.rotation' is not a rotation");
  d = good_;
  d["projector_from_camera"]["rotation"] = {-1, 0, 0, 0, 1, 0, 0, 0, 1};  // a reflection
  ExpectError(d, "'projector_from_camera.rotation' is not a rotation");
  d = good_;
  d["projector_from_camera"]["translation_mm"] = {0, 77.6};
  ExpectError(d, "'projector_from_camera.translation_mm'");
  d = good_;
  d.erase("projector");
  ExpectError(d, "'projector' is missing");
  d = good_;
  d["pattern"] = 8;
  ExpectError(d, "'pattern' must be an object");
  d = good_;
  d["pattern"]["spot_diameter_px"] = 12;
  ExpectError(d, "'pattern.spot_diameter_px' must not exceed");
  d = good_;
  d["pattern"]["matrix"] = "missing.png";
  ExpectError(d, "'pattern.matrix' names an unusable file");
  ExpectErrorText("{\"camera\": {\"width\": 2592,", "invalid JSON");
  ExpectErrorText("[1, 2, 3]", "must hold a JSON object");
  // nlohmann keeps the last of two: a value given twice is refused, by its path.
  std::string twice = good_.dump();
  twice.insert(twice.find("\"fx\":"), "\"fx\": 100.0, ");
  ExpectErrorText(twice, "field 'camera.fx' is given twice");
}

TEST_F(ModuleIoTest, RejectsTruncatedOrMissingPatternAndModule) {
  // A PNG cut in half.
  {
    std::ifstream in(dir_ / "pattern.png", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    std::ofstream(dir_ / "cut.png", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  json d = good_;
  d["pattern"]["matrix"] = "cut.png";
  ExpectError(d, "cannot decode image");
  d["pattern"]["matrix"] = ".";
  ExpectError(d, "'pattern.matrix' names an unusable file");
  EXPECT_THROW(LoadModule(dir_ / "no_such_module.json"), FileError);
  EXPECT_THROW(LoadModule(dir_), FileError);
}

TEST_F(ModuleIoTest, PatternMatrixWithAlphaIsReadByItsColour) {
  // The matrix exported as RGBA with an opaque alpha: the alpha is no spot.
  const BinaryArray pattern = DefaultPatternArray();
  cv::Mat4b rgba(pattern.rows, pattern.cols, cv::Vec4b(0, 0, 0, 255));
  for (int r = 0; r < pattern.rows; ++r) {
    for (int c = 0; c < pattern.cols; ++c) {
      if (pattern.at(r, c)) rgba(r, c) = cv::Vec4b(255, 255, 255, 255);
    }
  }
  ASSERT_TRUE(cv::imwrite((dir_ / "rgba.png").string(), rgba));
  EXPECT_EQ(ReadPatternMatrix(dir_ / "rgba.png"), pattern);
}

TEST_F(ModuleIoTest, NearUnitRotationWrittenWithFewDigitsIsAccepted) {
  json d = good_;
  const double c = 0.866025, s = 0.5;  // 30° about z, 6 digits
  d["projector_from_camera"]["rotation"] = {c, -s, 0, s, c, 0, 0, 0, 1};
  const LoadedModule loaded = LoadModule(Write(d.dump()));
  EXPECT_NEAR(loaded.module.projector_from_camera.rotation.norm(), 1.0, 1e-12);
}

// A calibrated module carries its standard deviations as an extra member; they come back in
// ModuleCalibrationResult::sigma's order, and a module without it has none.
TEST_F(ModuleIoTest, ACalibratedModuleCarriesItsStandardDeviations) {
  ModuleCalibrationResult r;
  for (std::size_t i = 0; i < r.sigma.size(); ++i) r.sigma[i] = 0.01 * static_cast<double>(i + 1);
  r.camera_rms_px = 0.09;
  ModuleDescription module = MakeDefaultModule({});
  module.pattern.matrix_path = "pattern.png";
  const fs::path plain = Write(ModuleToJson(module));
  EXPECT_FALSE(ModuleCalibrationSigma(LoadModule(plain).module, plain).has_value());
  module.source_json = ModuleCalibrationMember(r, 18, 20);
  const fs::path file = dir_ / "calibrated.json";
  SaveModule(file, module);
  const auto sigma = ModuleCalibrationSigma(LoadModule(file).module, file);
  ASSERT_TRUE(sigma.has_value());
  for (std::size_t i = 0; i < r.sigma.size(); ++i) EXPECT_DOUBLE_EQ((*sigma)[i], r.sigma[i]);
  json doc = json::parse(ModuleToJson(module));
  EXPECT_EQ(doc["calibration"]["poses_used"], 18);
  doc["calibration"]["sigma"]["projector"].erase("cy");
  try {
    const fs::path no_cy = Write(doc.dump(), "no_cy.json");
    ModuleCalibrationSigma(LoadModule(no_cy).module, no_cy);
    ADD_FAILURE() << "a sigma without projector cy was read";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("calibration.sigma.projector.cy"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace sewer3d
