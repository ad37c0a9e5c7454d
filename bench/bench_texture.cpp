// The RGB-D stage's colour steps per acquisition on the full 2592 x 1944 frame (docs/texture.md):
// the pipe prior joined to the depth map, the deblur of one texture image, the mapping of a
// triplet to the pattern instant, the shading correction. The frame is one rendered texture
// image of a DN300 concrete cylinder (motion-blurred at 100 mm/s, 4 ms) with its true depth cut
// to the middle of the image as the decoder's map; the second texture is the first shifted by
// 6 px along the travel (AKAZE's work is the same as on a real pair).
#include <benchmark/benchmark.h>

#include <opencv2/imgproc.hpp>

#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/texture/deblur.hpp"
#include "sewer3d/texture/depth_prior.hpp"
#include "sewer3d/texture/shading.hpp"
#include "sewer3d/texture/triplet_mapping.hpp"

namespace sewer3d {
namespace {

struct Frame {
  ModuleDescription module = MakeDefaultModule({});
  cv::Mat3f before, after;
  cv::Mat1f depth;  // the decoder's: the middle of the image only
  cv::Mat1f full;   // filled by the prior
  Rigid3d carrier_from_camera;
};

const Frame& TheFrame() {
  static const Frame frame = [] {
    Frame f;
    Scene scene;
    scene.type = Scene::Type::kCylinder;
    scene.diameter_mm = 300.0;
    RenderOptions options;
    options.supersampling = 1;
    options.images = RenderImages::kTexture;
    options.speed_mm_s = 100.0;
    options.exposure_ms = 4.0;
    const RenderedFrame r = RenderFrame(f.module, DefaultPatternArray(), scene, options);
    cv::Mat3f rgb;
    r.texture.convertTo(rgb, CV_32F, 1.0 / 255.0);
    cv::cvtColor(rgb, f.before, cv::COLOR_RGB2BGR);
    const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, 0, 0, 1, 6);
    cv::warpAffine(f.before, f.after, shift, f.before.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
    f.depth = cv::Mat1f(r.truth_depth.size(), std::numeric_limits<float>::quiet_NaN());
    const cv::Rect middle(f.depth.cols / 8, f.depth.rows / 8, 3 * f.depth.cols / 4,
                          3 * f.depth.rows / 4);
    r.truth_depth(middle).copyTo(f.depth(middle));
    // The scene's cylinder axis is camera y through the camera centre: the carrier's z axis
    // (camera x → carrier x, camera y → carrier z, the optical axis → carrier −y, up).
    Eigen::Matrix3d rotation;
    rotation << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    f.carrier_from_camera = Rigid3d(rotation, Eigen::Vector3d::Zero());
    f.full = FillDepthFromPrior(
        f.depth, PipePriorDepth(CameraModel(f.module.camera), f.carrier_from_camera, 300.0));
    return f;
  }();
  return frame;
}

void BM_PipePriorFill(benchmark::State& state) {
  const Frame& f = TheFrame();
  const cv::Mat2f normalised = NormalisedCoordinates(CameraModel(f.module.camera));
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        FillDepthFromPrior(f.depth, PipePriorDepth(normalised, f.carrier_from_camera, 300.0)));
  }
}
BENCHMARK(BM_PipePriorFill)->Unit(benchmark::kMillisecond);

void BM_Deblur(benchmark::State& state) {
  const Frame& f = TheFrame();
  const CameraModel camera(f.module.camera);
  DeblurReport last;
  for (auto _ : state) last = Deblur(f.before, f.full, camera, {0, 100, 0}, 4.0).report;
  state.counters["max_length_px"] = last.max_length_px;
  state.counters["bins"] = last.bins;
}
BENCHMARK(BM_Deblur)->Unit(benchmark::kMillisecond);

void BM_MapTripletToPattern(benchmark::State& state) {
  const Frame& f = TheFrame();
  const CameraModel camera(f.module.camera);
  TripletMappingReport last;
  for (auto _ : state) {
    last = MapTripletToPattern(f.before, f.after, f.full, camera, {0.0, 0.005, 0.010}).report;
  }
  state.counters["features"] = last.features_before;
  state.counters["inliers"] = last.inliers;
}
BENCHMARK(BM_MapTripletToPattern)->Unit(benchmark::kMillisecond);

void BM_ShadingCorrection(benchmark::State& state) {
  const Frame& f = TheFrame();
  const CameraModel camera(f.module.camera);
  ReferenceLightEstimator estimator(camera, ReferenceLightOptions{});
  estimator.Add(f.before, f.depth);
  const ShadingCorrector corrector(camera, *estimator.Estimate().reference, CorrectionOptions{});
  for (auto _ : state) benchmark::DoNotOptimize(corrector.Correct(f.before, f.full));
}
BENCHMARK(BM_ShadingCorrection)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sewer3d
