// The capture-run files (docs/formats.md) written and read back, and LoadRun's refusals of
// inconsistent runs, each naming the file and what is wrong.

#include "sewer3d/io/run_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/inclinometer_io.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/testing/matchers.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

// Two modules looking up and down, 90 mm apart along the carrier.
Rig TwoModuleRig() {
  ModuleDescription module = testing::SmallDefaultModule(648);
  module.pattern.matrix_path = "pattern.png";
  Rig rig;
  for (int k = 0; k < 2; ++k) {
    RigModule m;
    m.name = "m" + std::to_string(k);
    m.clock_h = k == 0 ? 12.0 : 6.0;
    m.module = module;
    Eigen::Matrix3d r;
    const double s = k == 0 ? 1.0 : -1.0;
    r << s, 0, 0, 0, 0, -s, 0, 1, 0;  // x along the clock, y along the axis, z radial
    m.carrier_from_camera = Rigid3d(r, Eigen::Vector3d(0, 0, 90.0 * k - 45.0));
    rig.modules.push_back(m);
  }
  return rig;
}

class RunIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("sewer3d_run_io_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A complete two-module run of two acquisitions with empty image files.
  void WriteRun() {
    rig_ = TwoModuleRig();
    WriteRig(dir_ / "rig.json", rig_);
    WritePatternMatrix(dir_ / "pattern.png", DefaultPatternArray());
    images_.clear();
    for (int j = 0; j < 2; ++j) {
      for (int m = 0; m < 2; ++m) {
        for (const ImageKind k : kImageKinds) {
          const double t = 0.1 * j + 0.02 * m + 0.005 * static_cast<int>(k);
          const std::string file = "images/m" + std::to_string(m) + "/" + std::to_string(j) + "_" +
                                   ImageKindName(k) + ".png";
          images_.push_back({m, j, k, t, 2.0, file});
          fs::create_directories((dir_ / file).parent_path());
          std::ofstream(dir_ / file) << "x";
        }
      }
    }
    std::sort(images_.begin(), images_.end(),
              [](const RunImage& a, const RunImage& b) { return a.time_s < b.time_s; });
    WriteIndex(dir_ / "acquisitions.csv", images_);
    WriteOdometry(dir_ / "odometry.csv", {{0.0, 0.0}, {0.05, 5.02}, {0.10, 9.98}, {0.15, 15.1}});
    RunInfo info;
    info.created_by = "test";
    info.seed = 7;
    info.acquisition_period_s = 0.1;
    WriteRunInfo(dir_ / "run.json", info, {2, 2, 12, 0.0});
  }

  std::string ErrorOf(const LoadRunOptions& options = {}) {
    try {
      LoadRun(dir_, options);
    } catch (const FileError& e) {
      std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      return what;
    }
    ADD_FAILURE() << "no error";
    return "";
  }

  fs::path dir_;
  Rig rig_;
  std::vector<RunImage> images_;
};

TEST_F(RunIoTest, WholeRunRoundTrips) {
  WriteRun();
  const CaptureRun run = LoadRun(dir_);
  EXPECT_EQ(run.folder, dir_);
  EXPECT_TRUE(run.info.complete);
  EXPECT_EQ(run.info.created_by, "test");
  EXPECT_EQ(run.info.seed, 7u);
  EXPECT_DOUBLE_EQ(run.info.acquisition_period_s, 0.1);
  ASSERT_EQ(run.rig.modules.size(), 2u);
  ASSERT_EQ(run.patterns.size(), 2u);
  EXPECT_EQ(run.patterns[1].rows, DefaultPatternArray().rows);
  for (size_t k = 0; k < 2; ++k) {
    const RigModule &a = rig_.modules[k], &b = run.rig.modules[k];
    EXPECT_EQ(a.name, b.name);
    EXPECT_DOUBLE_EQ(a.clock_h, b.clock_h);
    EXPECT_THAT(b.carrier_from_camera, testing::PoseNear(a.carrier_from_camera, 1e-7, 1e-9));
    EXPECT_DOUBLE_EQ(a.module.camera.fx, b.module.camera.fx);
  }
  ASSERT_EQ(run.images.size(), images_.size());
  for (size_t i = 0; i < images_.size(); ++i) {
    EXPECT_EQ(run.images[i].module, images_[i].module);
    EXPECT_EQ(run.images[i].counter, images_[i].counter);
    EXPECT_EQ(run.images[i].kind, images_[i].kind);
    EXPECT_NEAR(run.images[i].time_s, images_[i].time_s, 1e-6);  // written to 1 µs
    EXPECT_EQ(run.images[i].file, images_[i].file);
  }
  ASSERT_EQ(run.odometry.size(), 4u);
  EXPECT_DOUBLE_EQ(run.odometry[2].distance_mm, 9.98);
}

TEST_F(RunIoTest, ColorFilterRoundTripsDefaultsToNoneAndRefusesUnknownNames) {
  WriteRun();
  EXPECT_EQ(ReadRunInfo(dir_ / "run.json").color_filter, "none");
  RunInfo info = ReadRunInfo(dir_ / "run.json");
  info.color_filter = "RGGB";
  WriteRunInfo(dir_ / "run.json", info, {2, 2, 12, 0.0});
  EXPECT_EQ(LoadRun(dir_).info.color_filter, "RGGB");
  const std::string written = ReadTextFile(dir_ / "run.json");
  const std::string member = "\"color_filter\": \"RGGB\",";
  const size_t at = written.find(member);
  ASSERT_NE(at, std::string::npos) << written;
  std::string absent = written;
  absent.erase(at, member.size());
  WriteTextFile(dir_ / "run.json", absent);
  EXPECT_EQ(ReadRunInfo(dir_ / "run.json").color_filter, "none");  // runs from before
  std::string unknown = written;
  unknown.replace(at, member.size(), "\"color_filter\": \"rggb\",");
  WriteTextFile(dir_ / "run.json", unknown);
  const std::string error = ErrorOf();
  EXPECT_NE(error.find("run.json"), std::string::npos) << error;
  EXPECT_NE(error.find("color_filter"), std::string::npos) << error;
}

TEST_F(RunIoTest, KeepsAMissingImageMarkedAndChecksTheOdometry) {
  WriteRun();
  fs::remove(dir_ / images_[4].file);
  WriteOdometry(dir_ / "odometry.csv",
                {{0.0, 0.0}, {0.05, 5.0}, {0.10, -20.0}, {0.15, 14.9}, {0.60, 60.0}});
  const CaptureRun run = LoadRun(dir_);
  ASSERT_EQ(run.images.size(), images_.size());
  for (size_t i = 0; i < images_.size(); ++i) EXPECT_EQ(run.images[i].missing, i == 4) << i;
  // Line 4 (-20 mm after 5 mm) is dropped; 0.15 s to 0.60 s is a gap.
  ASSERT_EQ(run.odometry.size(), 4u);
  EXPECT_EQ(run.odometry[2].line, 5);
  ASSERT_EQ(run.odometry_findings.reversals.size(), 1u);
  EXPECT_EQ(run.odometry_findings.reversals[0].first_line, 4);
  ASSERT_EQ(run.odometry_findings.gaps.size(), 1u);
  EXPECT_EQ(run.odometry_findings.gaps[0].from_line, 5);
}

TEST_F(RunIoTest, RefusesInconsistentRuns) {
  WriteRun();
  images_[3].module = 2;
  WriteIndex(dir_ / "acquisitions.csv", images_);
  EXPECT_NE(ErrorOf().find("rig.json: modules: 2 modules, but acquisitions.csv lists"),
            std::string::npos)
      << ErrorOf();

  WriteRun();
  WriteOdometry(dir_ / "odometry.csv", {});
  EXPECT_NE(ErrorOf().find("odometry.csv: has no reading"), std::string::npos) << ErrorOf();

  WriteRun();
  images_[5] = images_[4];
  images_[5].time_s += 0.001;
  WriteIndex(dir_ / "acquisitions.csv", images_);
  EXPECT_NE(ErrorOf().find("is listed on line"), std::string::npos) << ErrorOf();  // one file
  images_[5].file += ".copy.png";
  WriteIndex(dir_ / "acquisitions.csv", images_);
  EXPECT_NE(ErrorOf().find("lists two"), std::string::npos) << ErrorOf();  // one image kind

  WriteRun();
  std::swap(images_[0], images_[1]);
  WriteIndex(dir_ / "acquisitions.csv", images_);
  EXPECT_NE(ErrorOf().find("acquisitions.csv: line 3: time_s 0 is before"), std::string::npos);

  WriteRun();
  images_[0].file = "../elsewhere.png";
  WriteIndex(dir_ / "acquisitions.csv", images_);
  EXPECT_NE(ErrorOf().find("inside the run folder"), std::string::npos);

  WriteRun();
  std::ofstream(dir_ / "acquisitions.csv")
      << "module,counter,image,time_s,exposure_ms,file\n0,0,pattern,abc,2,x.png\n";
  EXPECT_NE(ErrorOf().find("line 2: time_s 'abc' is not a number"), std::string::npos);

  WriteRun();
  WriteOdometry(dir_ / "odometry.csv", {{0.0, 0.0}, {0.05, 5.0}, {0.05, 5.1}});
  EXPECT_NE(ErrorOf().find("odometry.csv: line 4: time_s 0.05 does not increase"),
            std::string::npos);

  WriteRun();
  std::ofstream(dir_ / "rig.json") << R"({"format": "sewer3d-rig", "modules": [{"module": {}}]})";
  EXPECT_NE(ErrorOf().find("rig.json: modules[0].module"), std::string::npos);
}

TEST_F(RunIoTest, RefusesATypoOfAnOptionalRigFieldAndKeepsOtherTools) {
  // "clock_hh" would leave the module at the default 12 o'clock without a word.
  WriteRun();
  const std::string rig = ReadTextFile(dir_ / "rig.json");
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string text = rig;
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    WriteTextFile(dir_ / "rig.json", text);
  };
  with("\"clock_h\":", "\"clock_hh\":");
  EXPECT_NE(ErrorOf().find("'modules[0].clock_hh' is not a field sewer3d reads; did you mean "
                           "'modules[0].clock_h'?"),
            std::string::npos)
      << ErrorOf();
  // A member of another tool, far from every name sewer3d reads, is kept.
  with("\"clock_h\":", "\"serial_number\": \"SL-7\", \"clock_h\":");
  EXPECT_NO_THROW(LoadRun(dir_));
}

TEST_F(RunIoTest, IncompleteRunOnlyWhenAskedAndWithoutMissingImages) {
  WriteRun();
  RunInfo info;
  info.complete = false;
  WriteRunInfo(dir_ / "run.json", info, {2, 2, 12, 0.0});
  fs::remove(dir_ / images_.back().file);
  EXPECT_NE(ErrorOf().find("stopped part-way"), std::string::npos);
  const CaptureRun run = LoadRun(dir_, {.allow_incomplete = true});
  EXPECT_FALSE(run.info.complete);
  EXPECT_EQ(run.images.size(), images_.size() - 1);
}

// inclinometer.csv is optional: read when it is there, normalised, refused naming file and line.
TEST_F(RunIoTest, ReadsTheInclinometerWhereTheRunHasOne) {
  WriteRun();
  EXPECT_TRUE(LoadRun(dir_).inclinometer.empty());
  const Eigen::Vector3d tilted = Eigen::Vector3d(0.0, 1.0, 0.02).normalized();
  WriteInclinometer(dir_ / "inclinometer.csv",
                    {{0.0, Eigen::Vector3d::UnitY(), 0}, {0.05, tilted, 0}});
  const CaptureRun run = LoadRun(dir_);
  ASSERT_EQ(run.inclinometer.size(), 2u);
  EXPECT_EQ(run.inclinometer[1].line, 3);
  EXPECT_LT((run.inclinometer[1].down_in_carrier - tilted).norm(), 1e-8);
  // Halfway: the mean direction, normalised; outside the span or across a long gap: none.
  const auto mid = InclinometerDownAt(run.inclinometer, 0.025);
  ASSERT_TRUE(mid.has_value());
  EXPECT_LT((*mid - (Eigen::Vector3d::UnitY() + tilted).normalized()).norm(), 1e-8);
  EXPECT_FALSE(InclinometerDownAt(run.inclinometer, -0.01).has_value());
  EXPECT_FALSE(InclinometerDownAt(run.inclinometer, 0.06).has_value());
  EXPECT_FALSE(InclinometerDownAt(run.inclinometer, 0.025, 0.01).has_value());
  // A reading in g rather than unit length is a direction all the same.
  const fs::path file = dir_ / "inclinometer.csv";
  WriteTextFile(file, "time_s,down_x,down_y,down_z\n0,0,9.81,0\n0.05,0,9.81,0.1962\n");
  EXPECT_NEAR(LoadRun(dir_).inclinometer[1].down_in_carrier.z(), 0.02 / std::sqrt(1.0004), 1e-9);
  WriteTextFile(file, "time_s,down_x,down_y,down_z\n0,0,1,0\n0.05,0,0,0\n");
  EXPECT_NE(ErrorOf().find("inclinometer.csv: line 3: the direction (0, 0, 0) has no length"),
            std::string::npos)
      << ErrorOf();
  WriteTextFile(file, "time_s,down_x,down_y,down_z\n0,0,1,0\n0,0,1,0\n");
  EXPECT_NE(ErrorOf().find("inclinometer.csv: line 3: time_s 0 does not increase"),
            std::string::npos);
  WriteTextFile(file, "time_s,down_x,down_y,down_z\n0,0,nan,0\n");
  EXPECT_NE(ErrorOf().find("inclinometer.csv: line 2"), std::string::npos) << ErrorOf();
  WriteTextFile(file, "time_s,pitch,roll\n0,0,0\n");
  EXPECT_NE(ErrorOf().find("inclinometer.csv"), std::string::npos) << ErrorOf();
}

}  // namespace
}  // namespace sewer3d
