#include "sewer3d/decode/decoder.hpp"

#include <gtest/gtest.h>

#include "sewer3d/camera/default_module.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/triangulate/correspondences.hpp"

namespace sewer3d {
namespace {

struct Outcome {
  int spots = 0, decoded = 0, points = 0, wrong = 0;
  double rms_to_truth_mm = 0.0, max_to_truth_mm = 0.0;
};

// Decodes and triangulates a realistic render; errors against the true surface.
Outcome DecodeRender(const ModuleDescription& module, const Scene& scene, std::uint64_t seed) {
  const BinaryArray pattern = DefaultPatternArray();
  RenderOptions render;
  render.seed = seed;
  const RenderedFrame frame = RenderFrame(module, pattern, scene, render);
  Decoder decoder(module, pattern, PatternConstraints{}, DecoderOptions{});
  const DecodeResult decoded = decoder.Decode(frame.pattern);
  std::vector<CodedObservation> observations;
  for (const SpotCode& c : decoded.codes)
    observations.push_back({decoded.spots[c.spot].centre_px, c.row, c.col});
  auto points = TriangulateObservations(module, pattern.rows, pattern.cols, observations,
                                        TriangulationOptions{}, nullptr);
  RejectDepthOutliers(points, observations);
  Outcome out;
  out.spots = static_cast<int>(decoded.spots.size());
  out.decoded = static_cast<int>(decoded.codes.size());
  out.points = static_cast<int>(points.size());
  double sum2 = 0.0;
  for (const auto& p : points) {
    // Distance along the camera ray to the true surface.
    const auto hit = Intersect(scene, Eigen::Vector3d::Zero(), p.point_mm);
    const double error = hit ? (hit->point - p.point_mm).norm() : 1e9;
    if (error > 1.0) ++out.wrong;
    sum2 += error < 1.0 ? error * error : 0.0;
    out.max_to_truth_mm = std::max(out.max_to_truth_mm, error);
  }
  out.rms_to_truth_mm = std::sqrt(sum2 / std::max(1, out.points - out.wrong));
  return out;
}

void Record(const Outcome& o) {
  ::testing::Test::RecordProperty("spots", o.spots);
  ::testing::Test::RecordProperty("decoded", o.decoded);
  ::testing::Test::RecordProperty("points", o.points);
  ::testing::Test::RecordProperty("rms_mm", std::to_string(o.rms_to_truth_mm));
  ::testing::Test::RecordProperty("max_mm", std::to_string(o.max_to_truth_mm));
}

ModuleDescription Module(int width) {
  DefaultModuleOptions options;
  options.camera_width = width;
  options.camera_height = width * 3 / 4;
  return MakeDefaultModule(options);
}

TEST(Decoder, PlaneAt90mmDecodesAndTriangulates) {
  Scene plane;
  plane.distance_mm = 90.0;
  const Outcome o = DecodeRender(Module(648), plane, 1);
  Record(o);
  EXPECT_GT(o.decoded, 0.95 * o.spots);
  EXPECT_GT(o.points, 0.95 * o.spots);
  EXPECT_EQ(o.wrong, 0);
  EXPECT_LT(o.rms_to_truth_mm, 0.2);
}

TEST(Decoder, Dn300CylinderDecodesAndTriangulates) {
  Scene cylinder;
  cylinder.type = Scene::Type::kCylinder;
  cylinder.diameter_mm = 300.0;
  cylinder.axis_point_mm = {8.0, 0.0, -10.0};
  const Outcome o = DecodeRender(Module(648), cylinder, 2);
  Record(o);
  EXPECT_GT(o.points, 0.93 * o.spots);
  EXPECT_EQ(o.wrong, 0);
  EXPECT_LT(o.rms_to_truth_mm, 0.1);
}

}  // namespace
}  // namespace sewer3d
