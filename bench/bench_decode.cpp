// Decode stages on a full 2592 x 1944 pattern image (default module, DN300 concrete cylinder,
// realistic noise), next to OpenCV's ximgproc::niBlackThreshold and connectedComponentsWithStats.
#include <benchmark/benchmark.h>

#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>

#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/decode/niblack.hpp"
#include "sewer3d/decode/spots.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/triangulate/reconstruct_frame.hpp"

namespace sewer3d {
namespace {

const cv::Mat1b& PatternImage() {
  static const cv::Mat1b image = [] {
    Scene scene;
    scene.type = Scene::Type::kCylinder;
    scene.diameter_mm = 300.0;
    RenderOptions options;
    options.supersampling = 1;
    const RenderedFrame frame =
        RenderFrame(MakeDefaultModule({}), DefaultPatternArray(), scene, options);
    cv::Mat1b out;
    frame.pattern.convertTo(out, CV_8U);
    return out;
  }();
  return image;
}

void BM_NiblackRunningSums(benchmark::State& state) {
  const cv::Mat1b& image = PatternImage();  // rendered once, outside the timing
  NiblackBinariser binariser(NiblackOptions{});
  cv::Mat1b mask;
  for (auto _ : state) binariser.Apply(image, mask);
  state.SetItemsProcessed(state.iterations() * PatternImage().total());
}
BENCHMARK(BM_NiblackRunningSums)->Unit(benchmark::kMillisecond);

void BM_NiblackOpenCV(benchmark::State& state) {
  cv::Mat mask;
  for (auto _ : state) {
    cv::ximgproc::niBlackThreshold(PatternImage(), mask, 255, cv::THRESH_BINARY, 21, 0.3);
  }
  state.SetItemsProcessed(state.iterations() * PatternImage().total());
}
BENCHMARK(BM_NiblackOpenCV)->Unit(benchmark::kMillisecond);

void BM_SpotCentres(benchmark::State& state) {
  NiblackBinariser binariser(NiblackOptions{});
  cv::Mat1b mask;
  binariser.Apply(PatternImage(), mask);
  std::size_t spots = 0;
  SpotWorkspace workspace;
  for (auto _ : state)
    spots = DetectSpots(mask, binariser.excess(), SpotOptions{}, &workspace).size();
  state.counters["spots"] = static_cast<double>(spots);
}
BENCHMARK(BM_SpotCentres)->Unit(benchmark::kMillisecond);

void BM_ConnectedComponentsOpenCV(benchmark::State& state) {
  NiblackBinariser binariser(NiblackOptions{});
  cv::Mat1b mask;
  binariser.Apply(PatternImage(), mask);
  cv::Mat labels, stats, centroids;
  for (auto _ : state) cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
}
BENCHMARK(BM_ConnectedComponentsOpenCV)->Unit(benchmark::kMillisecond);

// The whole single-frame chain as `sewer3d reconstruct` and the pipeline run it: decode,
// triangulate, drop depth outliers, depth map (no texture).
// Argument 0: over the module's element mesh with holes drawn to the midpoints (the default);
// 1: the Delaunay triangles of the points (bridge_lost_spots), as before session 43; 2: the
// element mesh, holes from the last spots seen (session 43); 3: as 0 without the search for
// lost spots (LostSpotOptions::enabled, session 57); 4: as 0 without dropping the spots a step
// cut (CutSpotOptions::enabled, session 58).
void BM_ReconstructFrame(benchmark::State& state) {
  const cv::Mat1b& image = PatternImage();
  FrameReconstructionOptions options;
  options.bridge_lost_spots = state.range(0) == 1;
  options.holes_to_midpoints = state.range(0) != 2;
  options.lost_spots.enabled = state.range(0) != 3;
  options.cut_spots.enabled = state.range(0) != 4;
  FrameReconstructor reconstructor(MakeDefaultModule({}), DefaultPatternArray(),
                                   PatternConstraints{}, options);
  FrameReport last;
  for (auto _ : state) last = reconstructor.Reconstruct(image).report;
  state.counters["spots"] = last.spots_found;
  state.counters["points"] = last.points;
  state.counters["binarise_ms"] = last.seconds.binarise * 1e3;
  state.counters["spots_ms"] = last.seconds.spots * 1e3;
  state.counters["lattice_ms"] = last.seconds.lattice * 1e3;
  state.counters["codewords_ms"] = last.seconds.codewords * 1e3;
  state.counters["triangulate_ms"] = last.seconds.triangulate * 1e3;  // with outlier rejection
  state.counters["lost_spots_ms"] = last.seconds.lost_spots * 1e3;
  state.counters["lost_spots"] = last.lost_spots_found;
  state.counters["cut_by_step"] = last.rejected.cut_by_step;
  state.counters["depth_map_ms"] = last.seconds.depth_map * 1e3;
}
BENCHMARK(BM_ReconstructFrame)
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Arg(3)
    ->Arg(4)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sewer3d
