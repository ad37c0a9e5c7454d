// The model stage over the tiny simulated run (2 acquisitions × 6 modules, 648 × 486, 100 mm of
// travel past a joint offset 4 mm toward 12 o'clock): the centreline's diameter, the maps'
// displacement on the round wall and across the joint, the files of the workspace contract,
// a resumed stage that keeps what it wrote, and poses edited by hand refused.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <opencv2/core.hpp>
#include <vector>

#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/model_io.hpp"
#include "sewer3d/io/registration_io.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/pipeline/model_stage.hpp"
#include "sewer3d/pipeline/register_stage.hpp"
#include "sewer3d/pipeline/rgbd_stage.hpp"
#include "sewer3d/pipeline/tiny_run_sim_test.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

class ModelStageTiny : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / "sewer3d_model_stage_sim_test";
    fs::remove_all(dir_);
    testing::MakeTinyRun(dir_ / "run");
    run_ = LoadRun(dir_ / "run");
    Workspace ws(dir_ / "ws", run_.folder);
    RgbdStageOptions rgbd;
    rgbd.threads = 2;
    RunRgbdStage(run_, ws, rgbd);
    RegisterStageOptions reg;
    reg.threads = 2;
    RunRegisterStage(run_, ws, reg);
    options_.threads = 2;
    options_.tile_length_mm = 60.0;
    options_.keep_tiles = true;  // the resume test below takes one away
    report_ = RunModelStage(run_, ws, options_);
  }
  static void TearDownTestSuite() {
    if (!std::getenv("SEWER3D_KEEP")) fs::remove_all(dir_);
  }

  static fs::path dir_;
  static CaptureRun run_;
  static ModelStageOptions options_;
  static ModelStageReport report_;
};
fs::path ModelStageTiny::dir_;
CaptureRun ModelStageTiny::run_;
ModelStageOptions ModelStageTiny::options_;
ModelStageReport ModelStageTiny::report_;

// Median of the measured displacements at clocks within ±half_deg of `centre_deg` (0 = crown)
// and stations in [s0, s1] (model stations).
double BandMedian(const PipeMaps& m, double s0, double s1, double centre_deg, double half_deg) {
  std::vector<float> d;
  for (int r = 0; r < m.grid.rows; ++r) {
    const double s = m.grid.RowStationMm(r);
    if (s < s0 || s > s1) continue;
    for (int c = 0; c < m.grid.cols; ++c) {
      double deg = m.grid.ColClockRad(c) * 180.0 / std::numbers::pi - centre_deg;
      deg = std::remainder(deg, 360.0);
      if (std::abs(deg) > half_deg || m.coverage(r, c) != 1) continue;
      d.push_back(m.displacement_mm(r, c));
    }
  }
  if (d.empty()) return std::nan("");
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

TEST_F(ModelStageTiny, CentrelineAndFilesOfTheContract) {
  ASSERT_TRUE(report_.ok) << report_.message;
  EXPECT_EQ(report_.acquisitions, 12);
  // The fitted diameter: the true wall is DN300; depth noise ~0.05 mm and the joint's step
  // average out over thousands of samples.
  EXPECT_NEAR(2.0 * report_.centreline.radius_mm, 300.0, 0.6);
  EXPECT_DOUBLE_EQ(report_.nominal_diameter_mm, 300.0);
  EXPECT_GT(report_.measured_fraction, 0.2);
  const fs::path m = dir_ / "ws" / "model";
  for (const char* f :
       {"model.json", "texture.png", "displacement.png", "displacement.tiff", "coverage.png",
        "surface.ply", "mesh.obj", "mesh.mtl", "mesh.glb", "preview.png", "report.json"})
    EXPECT_TRUE(fs::exists(m / f)) << f;
  EXPECT_GT(report_.displaced_vertices, 1000u);
  // A file removed by hand makes `process` redo the stage.
  EXPECT_TRUE(ModelFilesPresent(m));
  fs::rename(m / "surface.ply", m / "surface.ply.away");
  EXPECT_FALSE(ModelFilesPresent(m));
  fs::rename(m / "surface.ply.away", m / "surface.ply");
}

TEST_F(ModelStageTiny, DisplacementIsRoundWallAndTheJointStep) {
  const PipeModel model = ReadPipeModel(dir_ / "ws" / "model");
  const PipeMaps& maps = model.maps;
  std::vector<float> all;
  for (int r = 0; r < maps.grid.rows; r += 7)
    for (int c = 0; c < maps.grid.cols; c += 7)
      if (maps.coverage(r, c) == 1) all.push_back(maps.displacement_mm(r, c));
  ASSERT_GT(all.size(), 1000u);
  std::nth_element(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(all.size() / 2),
                   all.end());
  EXPECT_LT(std::abs(all[all.size() / 2]), 0.5);
  // J1 lies at station 400 of the pipe, 50 mm past the carrier's first position (350): the
  // wall beyond it is 4 mm offset toward 12 o'clock, so at the invert (the modules that see
  // the joint look at 3–7 o'clock) the displacement steps by 4 mm · cos(±15°) on average
  // (3.95 mm), measured on each side next to the 8 mm gap. The smooth centreline passes
  // between the two offset sections, so each side looks tilted by ~0.015 mm/mm: ~0.3 mm less
  // step over these bands (measured 3.63 mm).
  const double before = BandMedian(maps, 36.0, 45.0, 180.0, 15.0);
  const double after = BandMedian(maps, 55.0, 64.0, 180.0, 15.0);
  RecordProperty("invert_before_mm", std::to_string(before));
  RecordProperty("invert_after_mm", std::to_string(after));
  ASSERT_TRUE(std::isfinite(before) && std::isfinite(after));
  EXPECT_NEAR(std::abs(after - before), 3.95, 0.5);
}

// The tiny run's modules carry the `paper` profile's calibration error, which reads each
// module's wall a few hundredths of a millimetre too far or too near: the seams show it, and
// the offsets estimated there bring the seams' cells together (model/module_offsets_test.cpp
// has the estimator against known offsets).
TEST_F(ModelStageTiny, EachModulesRangeOffsetComesFromTheSeams) {
  const ModuleOffsets& m = report_.module_offsets;
  ASSERT_TRUE(m.estimated) << m.why;
  ASSERT_EQ(m.range_mm.size(), 6u);
  double sum = 0.0;
  for (const double x : m.range_mm) {
    EXPECT_LT(std::abs(x), 0.3);  // a calibration's, not a pose's
    sum += x;
  }
  EXPECT_NEAR(sum, 0.0, 1e-9);
  EXPECT_GT(m.cells, 100);
  EXPECT_LT(m.rms_after_mm, m.rms_before_mm);
}

TEST_F(ModelStageTiny, ResumedStageKeepsItsTiles) {
  // As if killed while writing the last tile: its files are incomplete.
  const fs::path tiles = dir_ / "ws" / "model" / "tiles";
  const fs::path last_ply = tiles / ("tile_" + std::to_string(report_.tiles - 1) + "_surface.ply");
  ASSERT_TRUE(fs::exists(last_ply));
  fs::remove(last_ply);
  Workspace ws(dir_ / "ws", run_.folder);
  const ModelStageReport again = RunModelStage(run_, ws, options_);
  ASSERT_TRUE(again.ok);
  EXPECT_EQ(again.tiles_from_earlier_run, again.tiles - 1);
  EXPECT_EQ(again.grid.rows, report_.grid.rows);
  EXPECT_DOUBLE_EQ(again.measured_fraction, report_.measured_fraction);
}

TEST_F(ModelStageTiny, TilesGoWhenTheWholeRunFilesHoldTheMaps) {
  ModelStageOptions options = options_;
  options.keep_tiles = false;
  options.force = true;
  Workspace ws(dir_ / "ws", run_.folder);
  const ModelStageReport r = RunModelStage(run_, ws, options);
  ASSERT_TRUE(r.ok && r.whole_maps);
  EXPECT_FALSE(fs::exists(dir_ / "ws" / "model" / "tiles"));
  const PipeModel model = ReadPipeModel(dir_ / "ws" / "model");
  EXPECT_TRUE(model.info.tiles.empty());
  EXPECT_EQ(model.maps.grid.rows, report_.grid.rows);
  EXPECT_EQ(cv::countNonZero(model.maps.coverage == 1),
            static_cast<int>(std::lround(r.measured_fraction * r.grid.rows * r.grid.cols)));
}

TEST_F(ModelStageTiny, ARefusedNominalDiameterLeavesTheEarlierModel) {
  const fs::path model_json = dir_ / "ws" / "model" / "model.json";
  ASSERT_TRUE(fs::exists(model_json));
  const std::string before = ReadTextFile(model_json);
  ModelStageOptions options = options_;
  options.force = true;
  options.nominal_diameter_mm = 100.0;  // the pipe measures 300 mm
  Workspace ws(dir_ / "ws", run_.folder);
  EXPECT_THROW(RunModelStage(run_, ws, options), InvalidValue);
  ASSERT_TRUE(fs::exists(model_json));
  EXPECT_EQ(ReadTextFile(model_json), before);
}

TEST_F(ModelStageTiny, APoseMovedByHandIsRefused) {
  // One acquisition's pose 60 mm along the pipe, as a hand edit of poses.csv would put it: the
  // other five modules and the rig put the carrier where it was (within 0.5 mm here).
  const fs::path poses_csv = dir_ / "ws" / "registration" / "poses.csv";
  const std::string before = ReadTextFile(poses_csv);
  std::vector<RegistrationPoseRow> rows = ReadRegistrationPoses(poses_csv);
  const auto moved = std::find_if(rows.begin(), rows.end(), [](const RegistrationPoseRow& r) {
    return r.module == 1 && r.counter == 1;
  });
  ASSERT_NE(moved, rows.end());
  moved->world_from_camera.translation.z() += 60.0;
  WriteRegistrationPoses(poses_csv, rows);
  ModelStageOptions options = options_;
  options.force = true;
  try {
    Workspace ws(dir_ / "ws", run_.folder);
    RunModelStage(run_, ws, options);
    ADD_FAILURE() << "the moved pose was used";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("module 1's acquisition 1 puts the carrier"),
              std::string::npos)
        << e.what();
  }
  WriteTextFileAtomically(poses_csv, before);
}

}  // namespace
}  // namespace sewer3d
