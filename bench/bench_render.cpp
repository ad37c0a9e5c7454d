// Renderer throughput (samples/s) on the default module's full 2592 x 1944 frame and a
// reduced 648 x 486 one, for a DN300 concrete cylinder with the default (realistic) options;
// keypoints that feature detectors find on each material's texture image.
#include <benchmark/benchmark.h>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/sim/material.hpp"
#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/sim/scenario.hpp"

namespace sewer3d {
namespace {

void BM_RenderCylinder(benchmark::State& state) {
  DefaultModuleOptions module_options;
  module_options.camera_width = static_cast<int>(state.range(0));
  module_options.camera_height = module_options.camera_width * 3 / 4;
  const ModuleDescription module = MakeDefaultModule(module_options);
  Scene scene;
  scene.type = Scene::Type::kCylinder;
  scene.diameter_mm = 300.0;
  RenderOptions options;
  options.supersampling = static_cast<int>(state.range(1));
  std::int64_t samples = 0;
  for (auto _ : state) {
    const RenderedFrame frame = RenderFrame(module, DefaultPatternArray(), scene, options);
    samples += frame.samples;
  }
  state.counters["samples_per_s"] =
      benchmark::Counter(double(samples), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderCylinder)
    ->Args({648, 3})
    ->Args({2592, 1})
    ->Args({2592, 3})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
}  // namespace sewer3d

namespace sewer3d {
namespace {

// Ray hits on the demo preset's pipe world from carrier poses along the run: the cost that
// a whole-run render adds over a single cylinder.
void BM_PipeWorldIntersect(benchmark::State& state) {
  const Scenario s = PresetScenario("demo");
  const PipeGeometry pipe(s.world);
  const Trajectory trajectory(pipe, s.motion, s.seed);
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> rays;
  for (int i = 0; i < 4096; ++i) {
    const Rigid3d pose = trajectory.WorldFromCarrier(trajectory.DurationS() * (i % 64) / 64.0);
    const double a = kTwoPi * HashUniform(5, i, 1), b = 1.2 * (HashUniform(5, i, 2) - 0.5);
    rays.emplace_back(pose.translation,
                      pose.rotation * Eigen::Vector3d(std::sin(a), -std::cos(a), std::tan(b)));
  }
  std::int64_t hits = 0;
  for (auto _ : state) {
    for (const auto& [o, d] : rays) hits += pipe.Intersect(o, d).has_value();
  }
  state.counters["rays_per_s"] =
      benchmark::Counter(double(state.iterations()) * rays.size(), benchmark::Counter::kIsRate);
  benchmark::DoNotOptimize(hits);
}
BENCHMARK(BM_PipeWorldIntersect)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sewer3d

namespace sewer3d {
namespace {

// Keypoints that SIFT and AKAZE (OpenCV defaults) find on a texture image of a DN300 cylinder
// of each material, rendered full-size with the default options (S = 1 as in the presets) and
// stored as 8-bit like a run's images: how much the wall's texture gives feature-based
// registration (docs/simulator.md). The time is the render's.
void BM_TextureFeatures(benchmark::State& state) {
  const ModuleDescription module = MakeDefaultModule({});
  Scene scene;
  scene.type = Scene::Type::kCylinder;
  scene.diameter_mm = 300.0;
  scene.material = static_cast<Material>(state.range(0));
  RenderOptions options;
  options.images = RenderImages::kTexture;
  options.supersampling = 1;
  options.truth_depth = false;
  cv::Mat3w texture;
  for (auto _ : state) texture = RenderFrame(module, DefaultPatternArray(), scene, options).texture;
  cv::Mat texture8, grey;
  texture.convertTo(texture8, CV_8U, 255.0 / ((1 << options.sensor.bits) - 1));
  cv::cvtColor(texture8, grey, cv::COLOR_RGB2GRAY);
  std::vector<cv::KeyPoint> sift, akaze;
  cv::SIFT::create()->detect(grey, sift);
  cv::AKAZE::create()->detect(grey, akaze);
  state.counters["sift"] = static_cast<double>(sift.size());
  state.counters["akaze"] = static_cast<double>(akaze.size());
}
BENCHMARK(BM_TextureFeatures)
    ->ArgName("material")
    ->Arg(static_cast<int>(Material::kConcrete))
    ->Arg(static_cast<int>(Material::kVitrifiedClay))
    ->Arg(static_cast<int>(Material::kPlastic))
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
}  // namespace sewer3d
