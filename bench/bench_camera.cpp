// Camera model throughput: project and unproject over a full 2592 x 1944 image grid.
#include <benchmark/benchmark.h>

#include "sewer3d/camera/default_module.hpp"

namespace sewer3d {
namespace {

void BM_Unproject(benchmark::State& state) {
  const CameraModel camera(MakeDefaultModule({}).camera);
  for (auto _ : state) {
    double sum = 0.0;
    for (int v = 0; v < 1944; v += 8) {
      for (int u = 0; u < 2592; u += 8) sum += camera.Unproject({double(u), double(v)})->x();
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * (2592 / 8) * (1944 / 8));
}
BENCHMARK(BM_Unproject);

void BM_Project(benchmark::State& state) {
  const CameraModel camera(MakeDefaultModule({}).camera);
  for (auto _ : state) {
    double sum = 0.0;
    for (int i = 0; i < 100000; ++i) {
      sum += camera.Project({(i % 300 - 150) * 0.5, (i % 200 - 50) * 0.5, 150.0})->x();
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * 100000);
}
BENCHMARK(BM_Project);

}  // namespace
}  // namespace sewer3d
