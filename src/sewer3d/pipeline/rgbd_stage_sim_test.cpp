// The RGB-D stage over the tiny simulated run (2 acquisitions x 6 modules, 648 x 486): depth
// maps against the run's truth depth, clouds against depth maps, resuming after a kill or lost
// outputs, and bad images failing only their own acquisition.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/ply_io.hpp"
#include "sewer3d/io/rgbd_io.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/io/text_file.hpp"
#include "sewer3d/io/workspace_io.hpp"
#include "sewer3d/pipeline/rgbd_stage.hpp"
#include "sewer3d/pipeline/tiny_run_sim_test.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

class RgbdStageTiny : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / "sewer3d_rgbd_stage_sim_test";
    fs::remove_all(dir_);
    testing::MakeTinyRun(dir_ / "run");
    run_ = LoadRun(dir_ / "run");
    Workspace ws(dir_ / "ws", run_.folder);
    RgbdStageOptions options;
    options.threads = 2;
    report_ = RunRgbdStage(run_, ws, options);
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  // A copy of the finished workspace (the tests that change it leave the original alone).
  static fs::path CopyWorkspace(const std::string& name) {
    fs::path copy = dir_ / name;
    fs::remove_all(copy);
    fs::copy(dir_ / "ws", copy, fs::copy_options::recursive);
    return copy;
  }

  static fs::path dir_;
  static CaptureRun run_;
  static RgbdStageReport report_;
};
fs::path RgbdStageTiny::dir_;
CaptureRun RgbdStageTiny::run_;
RgbdStageReport RgbdStageTiny::report_;

TEST_F(RgbdStageTiny, EveryAcquisitionIsDoneWithTheContractFiles) {
  ASSERT_EQ(report_.acquisitions, 12);
  EXPECT_EQ(report_.done, 12);
  EXPECT_EQ(report_.failed, 0);
  EXPECT_EQ(report_.skipped, 0);
  EXPECT_GT(report_.points, 12 * 500);
  for (const RgbdAcquisitionSummary& r : report_.results) {
    SCOPED_TRACE("m" + std::to_string(r.module) + " " + std::to_string(r.counter));
    EXPECT_TRUE(r.complete);
    EXPECT_EQ(r.geometry.status, RgbdAcquisitionResult::Status::kDone);
    EXPECT_EQ(r.colour.status, RgbdAcquisitionResult::Status::kDone);
    const RgbdFiles files = RgbdAcquisitionFiles(dir_ / "ws" / "rgbd", r.module, r.counter);
    EXPECT_TRUE(fs::exists(files.geometry));
    const cv::Mat color = ReadImage(files.color, cv::IMREAD_UNCHANGED);
    EXPECT_EQ(color.type(), CV_8UC3);
    const cv::Mat depth = ReadImage(files.depth, cv::IMREAD_UNCHANGED);
    EXPECT_EQ(depth.type(), CV_32FC1);
    EXPECT_EQ(depth.size(), color.size());
    EXPECT_NE(ReadTextFile(files.cloud).find("property uchar red"), std::string::npos);
    EXPECT_NE(ReadTextFile(files.report).find("\"points\""), std::string::npos);
  }
  EXPECT_TRUE(fs::exists(dir_ / "ws" / "rgbd" / "m5" / "000001_depth.tiff"));
  const WorkspaceRecord record = ReadWorkspaceRecord(dir_ / "ws" / "workspace.json");
  ASSERT_EQ(record.stages.count("rgbd"), 1u);
  EXPECT_TRUE(record.stages.at("rgbd").done);
  EXPECT_EQ(record.stages.at("rgbd").notes.at("color"),
            "texture triplet: deblurred, mapped to the pattern instant, shading and colour "
            "corrected");
  EXPECT_EQ(record.stages.at("rgbd").options_json, RgbdOptionsJson({}));
}

// The decoder's precision on rendered images (docs/accuracy.md: 3–20 µm RMS at full size,
// 2592 px) scales with the pixel size: ~4x coarser here (648 px), and the tiny run renders with
// noise, motion blur (one-sample renders are blurred along each pixel's path since the
// simulator applies it afterwards) and the fine-structured concrete. The depth map adds linear
// interpolation between spots and the pixels where a triangle spans the joint's step. Measured:
// median 37–54 µm, p95 128–310 µm per module (m1 sees the joint's step); the bounds are about
// 1.5x the worst module. Coverage: the depth map covers the lit spot mesh, 74–88 % of the
// pixels that see the wall.
TEST_F(RgbdStageTiny, DepthMapsMatchTheTruthDepthOfThePatternImage) {
  for (int module = 0; module < 6; ++module) {
    std::vector<double> errors;
    long long truth_pixels = 0;
    for (int counter = 0; counter < 2; ++counter) {
      const RgbdFiles files = RgbdAcquisitionFiles(dir_ / "ws" / "rgbd", module, counter);
      const cv::Mat1f depth = ReadImage(files.depth, cv::IMREAD_UNCHANGED);
      const cv::Mat1f truth =
          ReadImage(dir_ / "run" / "truth" / "depth" /
                        (ImageStem(module, counter, ImageKind::kPattern) + ".tiff"),
                    cv::IMREAD_UNCHANGED);
      ASSERT_EQ(depth.size(), truth.size());
      for (int v = 0; v < depth.rows; ++v) {
        for (int u = 0; u < depth.cols; ++u) {
          if (!std::isfinite(truth(v, u))) continue;
          ++truth_pixels;
          if (std::isfinite(depth(v, u))) errors.push_back(std::abs(depth(v, u) - truth(v, u)));
        }
      }
    }
    const double median = Quantile(errors, 0.5), p95 = Quantile(errors, 0.95);
    const double coverage = static_cast<double>(errors.size()) / static_cast<double>(truth_pixels);
    RecordProperty(
        "m" + std::to_string(module),
        std::to_string(median) + " " + std::to_string(p95) + " " + std::to_string(coverage));
    SCOPED_TRACE("module m" + std::to_string(module) + ": median " + std::to_string(median) +
                 " mm, p95 " + std::to_string(p95) + " mm, coverage " + std::to_string(coverage));
    EXPECT_LT(median, 0.08);
    EXPECT_LT(p95, 0.45);
    EXPECT_GT(coverage, 0.6);
  }
}

TEST_F(RgbdStageTiny, CloudsAgreeWithTheirDepthMaps) {
  for (const RgbdAcquisitionSummary& r : report_.results) {
    SCOPED_TRACE("m" + std::to_string(r.module) + " " + std::to_string(r.counter));
    const RgbdFiles files = RgbdAcquisitionFiles(dir_ / "ws" / "rgbd", r.module, r.counter);
    const std::vector<Eigen::Vector3d> points = ReadPlyPoints(files.cloud);
    EXPECT_EQ(static_cast<int>(points.size()), r.geometry.frame.points);
    EXPECT_EQ(static_cast<long long>(points.size()), r.points);
    const cv::Mat1f depth = ReadImage(files.depth, cv::IMREAD_UNCHANGED);
    const CameraModel camera(run_.rig.modules[r.module].module.camera);
    // The depth map interpolates between the spots' detected centres, which lie within the
    // triangulation's reprojection limit (1 px) of the point's projection; so the 5 x 5 pixels
    // around the projection surround the centre and span the point's depth (the wall's slope
    // reaches 0.4 mm per pixel here, hence no fixed tolerance). On the border of the mesh the
    // neighbours lie on one side only: 0.15 mm of margin (a third of a pixel of slope).
    // Spots on the border of the mesh (no triangle reaches their pixels) have no depth there.
    int inside = 0, close = 0;
    for (const Eigen::Vector3d& p : points) {
      const std::optional<Eigen::Vector2d> px = camera.Project(p);
      ASSERT_TRUE(px.has_value());
      const int u0 = static_cast<int>(std::lround(px->x()));
      const int v0 = static_cast<int>(std::lround(px->y()));
      double lo = INFINITY, hi = -INFINITY;
      for (int v = std::max(0, v0 - 2); v <= std::min(depth.rows - 1, v0 + 2); ++v) {
        for (int u = std::max(0, u0 - 2); u <= std::min(depth.cols - 1, u0 + 2); ++u) {
          if (!std::isfinite(depth(v, u))) continue;
          lo = std::min<double>(lo, depth(v, u));
          hi = std::max<double>(hi, depth(v, u));
        }
      }
      if (!std::isfinite(lo)) continue;
      ++inside;
      if (p.z() > lo - 0.15 && p.z() < hi + 0.15) ++close;
    }
    EXPECT_GT(inside, 0.9 * static_cast<double>(points.size()));
    EXPECT_GT(close, 0.98 * inside);
  }
}

TEST_F(RgbdStageTiny, ARunAgainSkipsEverythingAndLostOutputsAreRedone) {
  const fs::path ws_folder = CopyWorkspace("ws_resume");
  RgbdStageOptions options;
  RgbdStageReport again;
  {
    Workspace ws(ws_folder, run_.folder);
    // While one process holds the workspace, another cannot open it.
    EXPECT_THROW(Workspace(ws_folder, run_.folder), FileError);
    again = RunRgbdStage(run_, ws, options);
  }
  EXPECT_EQ(again.skipped, 12);
  EXPECT_EQ(again.done, 0);
  EXPECT_EQ(again.points, report_.points);  // the report covers what earlier runs did
  // Lost: two reports (their other files stay, as after a kill before the report), the
  // colour of a third acquisition with its report, and a fourth's geometry and report.
  fs::remove(RgbdAcquisitionFiles(ws_folder / "rgbd", 0, 1).report);
  fs::remove(RgbdAcquisitionFiles(ws_folder / "rgbd", 3, 0).report);
  const RgbdFiles m5 = RgbdAcquisitionFiles(ws_folder / "rgbd", 5, 1);
  fs::remove(m5.color);
  fs::remove(m5.report);
  const RgbdFiles m1 = RgbdAcquisitionFiles(ws_folder / "rgbd", 1, 0);
  fs::remove(m1.geometry);
  fs::remove(m1.report);
  // And a fifth's cloud cut short (its report stays): the sizes its report recorded tell.
  const RgbdFiles m4 = RgbdAcquisitionFiles(ws_folder / "rgbd", 4, 1);
  fs::resize_file(m4.cloud, fs::file_size(m4.cloud) / 2);
  EXPECT_EQ(RgbdDamagedFile(m4), m4.cloud.string());
  // A temporary left by a killed writer is removed when the workspace is opened again.
  const fs::path stale = ws_folder / "rgbd" / "m2" / ".000000_color.png.tmp-999-0.png";
  std::ofstream(stale) << "partial";
  Workspace reopened(ws_folder, run_.folder);
  EXPECT_EQ(reopened.stale_temporaries_removed(), 1);
  EXPECT_FALSE(fs::exists(stale));
  again = RunRgbdStage(run_, reopened, options);
  EXPECT_EQ(again.done, 5);
  EXPECT_EQ(again.skipped, 7);
  EXPECT_EQ(again.failed, 0);
  EXPECT_EQ(again.results[2].geometry.status, RgbdAcquisitionResult::Status::kDone);  // m1 c0
  EXPECT_EQ(again.results[9].geometry.status, RgbdAcquisitionResult::Status::kDone);  // m4 c1
  EXPECT_EQ(RgbdDamagedFile(m4), "");
  EXPECT_EQ(again.results[1].geometry.status, RgbdAcquisitionResult::Status::kSkipped);
  EXPECT_TRUE(fs::exists(m5.color));
  EXPECT_TRUE(fs::exists(m5.report));
  EXPECT_EQ(again.points, report_.points);
}

TEST_F(RgbdStageTiny, AnInterruptedRunResumesWithoutRedoingFinishedAcquisitions) {
  const fs::path ws_folder = dir_ / "ws_interrupted";
  fs::remove_all(ws_folder);
  {
    Workspace ws(ws_folder, run_.folder);
    // Interrupted after the colour pass finished four acquisitions (a kill would leave at
    // most temporaries).
    EXPECT_THROW(RunRgbdStage(run_, ws, {},
                              [](const std::string& pass, int finished, int) {
                                if (pass == "colour" && finished == 4)
                                  throw std::runtime_error("killed");
                              }),
                 std::runtime_error);
  }
  EXPECT_FALSE(ReadWorkspaceRecord(ws_folder / "workspace.json").stages.at("rgbd").done);
  Workspace ws(ws_folder, run_.folder);
  const RgbdStageReport resumed = RunRgbdStage(run_, ws, {});
  EXPECT_EQ(resumed.skipped, 4);
  EXPECT_EQ(resumed.done, 8);
  for (const RgbdAcquisitionSummary& r : resumed.results)
    EXPECT_EQ(r.geometry.status, RgbdAcquisitionResult::Status::kSkipped);
  EXPECT_TRUE(ReadWorkspaceRecord(ws_folder / "workspace.json").stages.at("rgbd").done);
}

TEST_F(RgbdStageTiny, OtherOptionsAreRefusedUnlessForced) {
  const fs::path ws_folder = CopyWorkspace("ws_options");
  Workspace ws(ws_folder, run_.folder);
  RgbdStageOptions options;
  options.reconstruction.max_edge_steps = 4.0;
  EXPECT_THROW(RunRgbdStage(run_, ws, options), WorkspaceConflict);
  options.force = true;
  const RgbdStageReport forced = RunRgbdStage(run_, ws, options);
  EXPECT_EQ(forced.done, 12);
  EXPECT_EQ(forced.skipped, 0);
}

TEST_F(RgbdStageTiny, BadImagesFailOnlyTheirAcquisition) {
  const fs::path bad = dir_ / "run_bad";
  fs::remove_all(bad);
  fs::create_directories(bad);
  for (const auto& entry : fs::directory_iterator(run_.folder)) {
    if (entry.path().filename() != "truth")
      fs::copy(entry.path(), bad / entry.path().filename(), fs::copy_options::recursive);
  }
  const fs::path truncated = bad / "images" / (ImageStem(2, 1, ImageKind::kPattern) + ".png");
  fs::resize_file(truncated, fs::file_size(truncated) / 2);
  const fs::path small = bad / "images" / (ImageStem(4, 0, ImageKind::kTextureBefore) + ".png");
  ASSERT_TRUE(cv::imwrite(small.string(), cv::Mat3b(100, 120, cv::Vec3b(50, 60, 70))));
  // And odometry of one reading: no motion known at any image's time, so nothing deblurred.
  const std::string odometry = ReadTextFile(bad / "odometry.csv");
  const size_t second_row = odometry.find('\n', odometry.find('\n') + 1);
  WriteTextFileAtomically(bad / "odometry.csv", odometry.substr(0, second_row + 1));
  const CaptureRun run = LoadRun(bad);
  Workspace ws(dir_ / "ws_bad", run.folder);
  RgbdStageOptions options;
  options.threads = 2;
  const RgbdStageReport report = RunRgbdStage(run, ws, options);
  EXPECT_EQ(report.done, 10);
  ASSERT_EQ(report.failed, 2);
  const RgbdAcquisitionResult* first = report.FirstFailure();
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(first->module, 2);
  EXPECT_EQ(fs::path(first->file), truncated);
  EXPECT_NE(first->reason.find("truncated"), std::string::npos) << first->reason;
  ASSERT_EQ(report.results[8].module, 4);  // (module 4, counter 0)
  ASSERT_NE(report.results[8].Failure(), nullptr);
  const RgbdAcquisitionResult& wrong_size = *report.results[8].Failure();
  EXPECT_EQ(fs::path(wrong_size.file), small);
  EXPECT_NE(wrong_size.reason.find("120x100"), std::string::npos) << wrong_size.reason;
  EXPECT_FALSE(RgbdAcquisitionDone(RgbdAcquisitionFiles(dir_ / "ws_bad" / "rgbd", 2, 1)));
  const std::string json = ReadTextFile(dir_ / "ws_bad" / "rgbd" / "report.json");
  EXPECT_NE(json.find(truncated.string()), std::string::npos);
  EXPECT_FALSE(ReadWorkspaceRecord(dir_ / "ws_bad" / "workspace.json").stages.at("rgbd").done);
  EXPECT_NE(report.color_source.find("deblurred (for 0 of 10: no odometry"), std::string::npos)
      << report.color_source;
  const auto said = std::find_if(report.warnings.begin(), report.warnings.end(), [](const auto& w) {
    return w.find("10 of 10 acquisitions not deblurred") != std::string::npos;
  });
  EXPECT_NE(said, report.warnings.end());
}

}  // namespace
}  // namespace sewer3d
