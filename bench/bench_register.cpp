// Pairwise registration per pair (docs/registration.md): feature-based (SIFT, matches, RANSAC,
// Gauss–Newton) and projection-based (point-to-plane from the odometry guess) on two views of
// a DN300 concrete wall 65 mm apart along the pipe (the along-pipe neighbour of the default
// capture), at the reduced 648 × 486 size the tests and the demo use and at the full
// 2592 × 1944. Colour: the renderer's texture image; depth: the true depth map (the decoder's
// work is bench_decode's), cut to the middle 3/4 of the image like the lit part.
#include <benchmark/benchmark.h>

#include <map>
#include <opencv2/imgproc.hpp>

#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/register/feature_registration.hpp"
#include "sewer3d/register/projection_registration.hpp"
#include "sewer3d/sim/renderer.hpp"

namespace sewer3d {
namespace {

constexpr double kStepMm = 65.0;  // the default capture's advance between acquisitions

struct Pair {
  ModuleDescription module;
  RgbdImage a, b;
  Rigid3d a_from_b;  // truth: b's camera kStepMm further along the pipe (camera y)
};

RgbdImage View(const ModuleDescription& module, double station_shift_mm) {
  Scene scene;
  scene.type = Scene::Type::kCylinder;
  scene.material = Material::kConcrete;
  scene.material_seed = 7;
  scene.diameter_mm = 300.0;
  scene.axis = Eigen::Vector3d::UnitY();
  scene.axis_point_mm = Eigen::Vector3d(4.0, -station_shift_mm, -12.0);
  RenderOptions options;
  options.images = RenderImages::kTexture;
  options.supersampling = 1;
  const RenderedFrame frame = RenderFrame(module, DefaultPatternArray(), scene, options);
  RgbdImage out;
  frame.texture.convertTo(out.color_bgr, CV_8U);
  cv::cvtColor(out.color_bgr, out.color_bgr, cv::COLOR_RGB2BGR);
  out.depth = cv::Mat1f(frame.truth_depth.size(), std::numeric_limits<float>::quiet_NaN());
  const cv::Rect middle(out.depth.cols / 8, out.depth.rows / 8, 3 * out.depth.cols / 4,
                        3 * out.depth.rows / 4);
  frame.truth_depth(middle).copyTo(out.depth(middle));
  return out;
}

const Pair& ThePair(int width) {
  static std::map<int, Pair> pairs;
  auto it = pairs.find(width);
  if (it == pairs.end()) {
    DefaultModuleOptions o;
    o.camera_width = width;
    o.camera_height = width * 3 / 4;
    Pair p;
    p.module = MakeDefaultModule(o);
    p.a = View(p.module, 0.0);
    p.b = View(p.module, kStepMm);
    p.a_from_b = Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.0, kStepMm, 0.0));
    it = pairs.emplace(width, std::move(p)).first;
  }
  return it->second;
}

void BM_FeatureRegistration(benchmark::State& state) {
  const Pair& p = ThePair(static_cast<int>(state.range(0)));
  const CameraModel camera(p.module.camera);
  FeatureRegistrationResult last;
  for (auto _ : state) last = RegisterFeatures(p.a, camera, p.b, camera, {});
  state.counters["inliers"] = last.inliers;
  state.counters["error_mm"] = (last.a_from_b.translation - p.a_from_b.translation).norm();
}
BENCHMARK(BM_FeatureRegistration)->Arg(648)->Arg(2592)->Unit(benchmark::kMillisecond);

void BM_ProjectionRegistration(benchmark::State& state) {
  const Pair& p = ThePair(static_cast<int>(state.range(0)));
  const CameraModel camera(p.module.camera);
  // The odometry's guess: 1 mm short along the pipe, 0.5 mm across.
  const Rigid3d guess(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.5, kStepMm - 1.0, 0.0));
  ProjectionRegistrationResult last;
  for (auto _ : state) last = RegisterProjection(p.a.depth, camera, p.b.depth, camera, guess, {});
  state.counters["correspondences"] = last.correspondences;
  state.counters["iterations"] = last.report.iterations;
}
BENCHMARK(BM_ProjectionRegistration)->Arg(648)->Arg(2592)->Unit(benchmark::kMillisecond);

// With the texture term (photometric.hpp), from a guess 10 mm short along the pipe (a slipping
// counter): the search of the weak directions, then the joint solve.
void BM_TexturedProjectionRegistration(benchmark::State& state) {
  const Pair& p = ThePair(static_cast<int>(state.range(0)));
  const CameraModel camera(p.module.camera);
  const Rigid3d guess(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.5, kStepMm - 10.0, 0.0));
  ProjectionRegistrationResult last;
  for (auto _ : state) last = RegisterProjection(p.a, camera, p.b, camera, guess, {});
  state.counters["textured"] = last.report.photometric ? 1 : 0;
  state.counters["error_mm"] = (last.a_from_b.translation - p.a_from_b.translation).norm();
  state.counters["iterations"] = last.report.iterations;
}
BENCHMARK(BM_TexturedProjectionRegistration)->Arg(648)->Arg(2592)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sewer3d
