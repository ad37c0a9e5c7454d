// The tiny preset written as a capture run, then read back through the documented files only:
// every image's ground-truth depth must agree with the world seen through the true pose.

#include "sewer3d/simio/simulate_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/io/image_io.hpp"
#include "sewer3d/io/run_io.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/simio/scenario_io.hpp"
#include "sewer3d/simio/truth_io.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

namespace fs = std::filesystem;

class TinyRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / "sewer3d_tiny_run_test";
    fs::remove_all(dir_);
    const Scenario s = PresetScenario("tiny");
    int calls = 0;
    result_ = SimulateRun(s, testing::SmallDefaultModule(s.camera_width), DefaultPatternArray(),
                          dir_, [&](int done, int total) {
                            ++calls;
                            EXPECT_LE(done, total);
                          });
    calls_ = calls;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static fs::path dir_;
  static SimulatedRun result_;
  static int calls_;
};
fs::path TinyRun::dir_;
SimulatedRun TinyRun::result_;
int TinyRun::calls_ = 0;

TEST_F(TinyRun, TruthDepthAgreesWithTheWorldThroughTheTruePose) {
  const CaptureRun run = LoadRun(dir_);
  const std::vector<RunImage>& index = run.images;
  const auto poses = ReadTruthPoses(dir_ / "truth" / "poses.csv");
  const Scenario scenario = ReadScenario(dir_ / "truth" / "scenario.json");
  const PipeGeometry pipe(scenario.world);
  ASSERT_EQ(run.rig.modules.size(), 6u);
  ASSERT_EQ(index.size(), poses.size());
  ASSERT_EQ(static_cast<int>(index.size()), result_.images);
  EXPECT_EQ(calls_, result_.images);
  double worst = 0.0;
  int on_steps = 0;
  for (size_t i = 0; i < index.size(); ++i) {
    const RunImage& e = index[i];
    ASSERT_EQ(poses[i].module, e.module);
    ASSERT_EQ(poses[i].time_s, e.time_s);
    const RigModule& m = run.rig.modules[e.module];
    const cv::Mat image = ReadImage(dir_ / e.file, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(image.cols, m.module.camera.width);
    ASSERT_EQ(image.rows, m.module.camera.height);
    ASSERT_EQ(image.channels(), e.kind == ImageKind::kPattern ? 1 : 3);
    fs::path depth_file = dir_ / "truth" / "depth" / fs::path(e.file).lexically_relative("images");
    depth_file.replace_extension(".tiff");
    const cv::Mat depth = ReadImage(depth_file, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(depth.type(), CV_32F);
    const CameraModel camera(m.module.camera);
    const Rigid3d world_from_camera = poses[i].world_from_carrier * m.carrier_from_camera;
    int finite = 0, checked = 0;
    for (int v = 0; v < depth.rows; v += 5) {
      for (int u = 0; u < depth.cols; u += 5) {
        ++checked;
        const float z = depth.at<float>(v, u);
        if (!std::isfinite(z)) continue;
        ++finite;
        const auto xy = camera.Unproject({double(u), double(v)});
        ASSERT_TRUE(xy);
        const Eigen::Vector3d p = world_from_camera * (z * Eigen::Vector3d(xy->x(), xy->y(), 1.0));
        const double g = pipe.SignedDistanceMm(p);
        if (std::abs(g) < 2e-3) {
          worst = std::max(worst, std::abs(g));
          continue;
        }
        // Not on the wall function: then on the face of a step (a joint offset), which the
        // signed distance crosses within a hair along the pipe.
        const Eigen::Vector3d along =
            0.02 * (pipe.PathFrame(pipe.Locate(p).station_mm).rotation * Eigen::Vector3d::UnitZ());
        const bool on_step =
            pipe.SignedDistanceMm(p - along) * pipe.SignedDistanceMm(p + along) < 0.0;
        ++on_steps;
        EXPECT_TRUE(on_step) << e.file << " pixel " << u << "," << v << ": " << g
                             << " mm off the wall";
      }
    }
    EXPECT_GT(finite, 0.95 * checked) << e.file;
  }
  std::printf(
      "%d images, largest distance of a truth-depth point from the wall %.2e mm (%d on step "
      "faces)\n",
      result_.images, worst, on_steps);
  EXPECT_LT(worst,
            2e-3);  // float32 depth at ~150 mm is exact to ~1e-5 mm; poses written to 1e-6 mm
}

TEST_F(TinyRun, RunFolderLoadsCompleteAndMatchesThePlan) {
  EXPECT_GE(result_.plan.acquisitions, 2);
  EXPECT_EQ(result_.images, result_.plan.acquisitions * 18);
  const CaptureRun run = LoadRun(dir_);  // checks that every listed image exists
  EXPECT_TRUE(run.info.complete);
  EXPECT_EQ(run.info.scenario, "tiny");
  EXPECT_NEAR(run.info.acquisition_period_s, result_.plan.period_s, 1e-9);
  EXPECT_EQ(static_cast<int>(run.images.size()), result_.images);
  ASSERT_EQ(run.patterns.size(), 6u);
  const auto acquisitions = GroupAcquisitions(run.images);
  EXPECT_EQ(static_cast<int>(acquisitions.size()), result_.plan.acquisitions * 6);
  for (const Acquisition& a : acquisitions) {
    for (const ImageKind k : kImageKinds) EXPECT_GE(a.Image(k), 0);
  }
  // Odometry covers the run at 20 Hz and reads within a few mm of the planned travel.
  ASSERT_GE(run.odometry.size(), 2u);
  EXPECT_NEAR(run.odometry[1].time_s - run.odometry[0].time_s, 0.05, 1e-6);
  EXPECT_GE(run.odometry.back().time_s, run.images.back().time_s);
  EXPECT_GT(result_.bytes, 1000u);
  for (const NeighbourOverlap& o : result_.overlap) EXPECT_GT(o.overlap_deg, 5.0);
}

std::string FileText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A simulation killed part-way (run.json not complete, some shots' files missing, a writer's
// temporary left) goes on from the images it finished and ends with the uninterrupted run.
TEST_F(TinyRun, AnInterruptedSimulationResumesToTheSameFiles) {
  const fs::path cut = dir_.string() + "_cut";
  fs::remove_all(cut);
  fs::copy(dir_, cut, fs::copy_options::recursive);
  const std::string info = FileText(cut / "run.json");
  const std::string complete = "\"complete\": true";
  ASSERT_NE(info.find(complete), std::string::npos);
  std::ofstream(cut / "run.json") << std::string(info).replace(info.find(complete), complete.size(),
                                                               "\"complete\": false");
  const CaptureRun run = LoadRun(dir_);
  ASSERT_GE(run.images.size(), 8u);
  const std::vector<std::size_t> lost_image = {0, 5, run.images.size() - 1};
  for (std::size_t i : lost_image) fs::remove(cut / run.images[i].file);
  // A shot whose image was written but not its truth depth is rendered again as well.
  const RunImage& half = run.images[3];
  fs::remove(cut / "truth" / "depth" / (ImageStem(half.module, half.counter, half.kind) + ".tiff"));
  const fs::path temporary = cut / "images" / ".x.png.tmp-1-0.png";
  std::ofstream(temporary) << "half an image";
  const fs::path kept_image = cut / run.images[1].file;
  const auto kept_time = fs::last_write_time(kept_image);

  const Scenario s = PresetScenario("tiny");
  int first_done = -1;
  const SimulatedRun resumed = SimulateRun(s, testing::SmallDefaultModule(s.camera_width),
                                           DefaultPatternArray(), cut, [&](int done, int) {
                                             if (first_done < 0) first_done = done;
                                           });
  EXPECT_EQ(resumed.images_kept, result_.images - 4);
  EXPECT_EQ(first_done, result_.images - 4);  // the progress starts where the last run stopped
  EXPECT_TRUE(LoadRun(cut).info.complete);
  EXPECT_FALSE(fs::exists(temporary));
  EXPECT_EQ(fs::last_write_time(kept_image), kept_time);  // not rendered again
  for (const auto& e : fs::recursive_directory_iterator(dir_)) {
    const fs::path rel = fs::relative(e.path(), dir_);
    if (!e.is_regular_file() || rel == "run.json") continue;
    EXPECT_EQ(FileText(cut / rel), FileText(e.path())) << rel;
  }
  fs::remove_all(cut);
}

}  // namespace
}  // namespace sewer3d

namespace sewer3d {
namespace {

// Per pixel, red over blue of image / albedo: the white balance times the ring light's and
// the lens's colour at that pixel, which are the same for every module (NaN where the pixel is
// dark, saturated or sees no surface).
cv::Mat1f RedOverBlue(const cv::Mat& image_bgr, const cv::Mat& albedo_bgr16) {
  cv::Mat1f ratio(image_bgr.size(), NAN);
  for (int v = 0; v < image_bgr.rows; ++v) {
    for (int u = 0; u < image_bgr.cols; ++u) {
      const cv::Vec3w& a = albedo_bgr16.at<cv::Vec3w>(v, u);
      const cv::Vec3b& p = image_bgr.at<cv::Vec3b>(v, u);
      if (std::min(p[0], p[2]) < 40 || std::max(p[0], p[2]) > 250 || std::min(a[0], a[2]) == 0)
        continue;
      ratio(v, u) = static_cast<float>((double(p[2]) / a[2]) / (double(p[0]) / a[0]));
    }
  }
  return ratio;
}

TEST_F(TinyRun, TextureImagesCarryEachModulesWhiteBalanceAndHaveTruthAlbedo) {
  const CaptureRun run = LoadRun(dir_);
  EXPECT_EQ(run.info.color_filter, "none");
  const Scenario scenario = ReadScenario(dir_ / "truth" / "scenario.json");
  EXPECT_TRUE(scenario.truth_albedo);
  std::ifstream gains_file(dir_ / "truth" / "camera_gains.csv");
  std::string line;
  std::getline(gains_file, line);
  EXPECT_EQ(line, "module,gain_r,gain_g,gain_b");
  std::vector<Eigen::Vector3d> gains;
  for (int m; std::getline(gains_file, line);) {
    Eigen::Vector3d g;
    ASSERT_EQ(std::sscanf(line.c_str(), "%d,%lf,%lf,%lf", &m, &g.x(), &g.y(), &g.z()), 4);
    EXPECT_EQ(m, static_cast<int>(gains.size()));
    EXPECT_LT((g - CameraWhiteBalance(scenario, m)).norm(), 1e-5);  // written to 1e-6
    gains.push_back(g);
  }
  ASSERT_EQ(gains.size(), 6u);
  double spread = 0.0;
  for (const Eigen::Vector3d& g : gains) spread = std::max(spread, std::abs(g.x() - gains[0].x()));
  EXPECT_GT(spread, 0.01);  // σ = 4 %: the modules' cameras differ

  // Each module's first texture image: pixel by pixel, its red/blue balance over module 0's
  // is the ratio of their gains; the median over the pixels agrees within 1 % (8-bit noise of
  // ~1 % per pixel averages out; the ambient light, colourless, shifts pixels in shadow).
  std::vector<cv::Mat1f> red_over_blue(6);
  for (const RunImage& e : run.images) {
    if (e.kind == ImageKind::kPattern) continue;
    const fs::path albedo = dir_ / "truth" / "albedo" / ImageStem(e.module, e.counter, e.kind);
    const cv::Mat srgb = ReadImage(albedo.string() + ".png", cv::IMREAD_UNCHANGED);
    const cv::Mat linear = ReadImage(albedo.string() + "_linear.png", cv::IMREAD_UNCHANGED);
    ASSERT_EQ(srgb.type(), CV_8UC3);
    ASSERT_EQ(linear.type(), CV_16UC3);
    if (e.counter != 0 || e.kind != ImageKind::kTextureBefore) continue;
    const cv::Mat image = ReadImage(dir_ / e.file, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(linear.size(), image.size());
    red_over_blue[e.module] = RedOverBlue(image, linear);
  }
  for (int m = 1; m < 6; ++m) {
    std::vector<float> relative;
    for (int v = 0; v < red_over_blue[0].rows; ++v) {
      for (int u = 0; u < red_over_blue[0].cols; ++u) {
        const float r = red_over_blue[m](v, u) / red_over_blue[0](v, u);
        if (std::isfinite(r)) relative.push_back(r);
      }
    }
    ASSERT_GT(relative.size(), 10000u);
    std::nth_element(relative.begin(), relative.begin() + relative.size() / 2, relative.end());
    const double expected = (gains[m].x() / gains[m].z()) / (gains[0].x() / gains[0].z());
    EXPECT_NEAR(relative[relative.size() / 2], expected, 0.01) << "module " << m;
  }
}

}  // namespace
}  // namespace sewer3d
