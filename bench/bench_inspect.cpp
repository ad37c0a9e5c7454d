// The inspect stage's search for cracks in the texture (docs/inspection.md, "Cracks in the
// texture") on 300 mm of DN300 at the model's 0.2 mm: the simulator's concrete albedo with a
// crack 100 mm long and 1.5 mm open drawn into it; m_per_s: metres of pipe searched a second.
#include <benchmark/benchmark.h>

#include <cmath>
#include <opencv2/core/utility.hpp>

#include "sewer3d/core/units.hpp"
#include "sewer3d/inspect/coarse_map.hpp"
#include "sewer3d/inspect/texture_cracks.hpp"
#include "sewer3d/model/pipe_map.hpp"
#include "sewer3d/sim/material.hpp"

namespace sewer3d {
namespace {

constexpr double kRadius = 150.0, kLengthMm = 300.0;

const CoarseMap& TheMap() {
  static const CoarseMap map = [] {
    PipeMaps maps;
    maps.grid = MakeMapGrid(0.0, kLengthMm, kRadius, 0.2);
    const MapGrid& g = maps.grid;
    maps.texture.create(g.rows, g.cols);
    maps.displacement_mm = cv::Mat1f::zeros(g.rows, g.cols);
    maps.coverage = cv::Mat1b(g.rows, g.cols, static_cast<unsigned char>(Coverage::kMeasured));
    const double a = DegToRad(20.0), arc_mm = 2.0 * std::numbers::pi * kRadius / g.cols;
    cv::parallel_for_(cv::Range(0, g.rows), [&](const cv::Range& rows) {
      for (int r = rows.start; r < rows.end; ++r) {
        for (int c = 0; c < g.cols; ++c) {
          const double s = g.RowStationMm(r), x = (c + 0.5) * arc_mm;
          Eigen::Vector3d rgb = MaterialAlbedo(Material::kConcrete, 1, {x, s});
          const double ds = s - 150.0, dx = x - 0.375 * g.cols * arc_mm;
          const double along = ds * std::cos(a) + dx * std::sin(a);
          const double across = -ds * std::sin(a) + dx * std::cos(a);
          if (std::abs(along) < 50.0 && std::abs(across) < 0.75) rgb *= 0.25;
          maps.texture(r, c) = cv::Vec3b(cv::saturate_cast<unsigned char>(255.0 * rgb.z()),
                                         cv::saturate_cast<unsigned char>(255.0 * rgb.y()),
                                         cv::saturate_cast<unsigned char>(255.0 * rgb.x()));
        }
      }
    });
    CoarseMapBuilder builder(g, 1.0, TextureCrackOptions{}.cell_mm);
    builder.Add(maps);
    return builder.Finish();
  }();
  return map;
}

void BM_FindTextureCracks(benchmark::State& state) {
  const CoarseMap& map = TheMap();
  std::size_t found = 0;
  for (auto _ : state) {
    found = FindTextureCracks(map, kRadius, {}, {}).size();
    benchmark::DoNotOptimize(found);
  }
  state.counters["cracks"] = static_cast<double>(found);
  // Metres of pipe searched per second.
  state.counters["m_per_s"] =
      benchmark::Counter(kLengthMm / 1000.0, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_FindTextureCracks)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace sewer3d
