// Renderer throughput (samples/s) on the default module's full 2592 x 1944 frame and a
// reduced 648 x 486 one, for a DN300 concrete cylinder with the default (realistic) options.
#include <benchmark/benchmark.h>

#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/sim/renderer.hpp"

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
  state.counters["samples_per_s"] = benchmark::Counter(double(samples), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderCylinder)->Args({648, 3})->Args({2592, 1})->Args({2592, 3})
    ->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace
}  // namespace sewer3d
