// The decoder on rendered frames with realistic noise (sim/): every decoded array position
// checked against the element the true surface puts under the spot.

#include <gtest/gtest.h>

#include <cmath>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/decode/decoder.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/sim/renderer.hpp"
#include "sewer3d/sim/spot_errors.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

struct Outcome {
  int spots = 0, decoded = 0, wrong = 0;
  int largest_group = 0;  ///< spots in the largest lattice group
  int conflicts = 0;      ///< LatticeLabels::conflicts
};

// Decodes a realistic render; a decode is wrong when the projector element whose centre is
// nearest to where the spot's camera ray meets the true surface differs, modulo the array.
// `bits`: the sensor's ADC; `stretch`: the digital numbers multiplied by it (a 16-bit file
// using its full range).
Outcome DecodeRender(const ModuleDescription& module, const Scene& scene, std::uint64_t seed,
                     int bits = 8, double stretch = 1.0, const SpotErrors& errors = {},
                     int supersampling = RenderOptions{}.supersampling) {
  const BinaryArray pattern = DefaultPatternArray();
  RenderOptions render;
  render.seed = seed;
  render.images = RenderImages::kPattern;
  render.sensor.bits = bits;
  render.spot_errors = errors;
  render.supersampling = supersampling;
  const RenderedFrame frame = RenderFrame(module, pattern, scene, render);
  cv::Mat1w image = frame.pattern * stretch;
  Decoder decoder(module, pattern, PatternConstraints{}, DecoderOptions{});
  const DecodeResult decoded = decoder.Decode(image);
  const std::vector<CodedObservation> observations = CodedObservations(decoded);
  EXPECT_EQ(observations.size(), decoded.codes.size());
  const CameraModel camera(module.camera), projector(module.projector);
  const PatternLayout& layout = module.pattern;
  const auto mod = [](int i, int n) { return (i % n + n) % n; };
  Outcome out;
  out.spots = static_cast<int>(decoded.spots.size());
  out.decoded = static_cast<int>(observations.size());
  std::vector<int> group_size(decoded.lattice.groups, 0);
  for (const int g : decoded.lattice.group)
    if (g >= 0) ++group_size[g];
  for (const int size : group_size) out.largest_group = std::max(out.largest_group, size);
  out.conflicts = decoded.lattice.conflicts;
  for (const CodedObservation& o : observations) {
    const auto ray = camera.Ray(o.camera_px);
    const auto hit = ray ? Intersect(scene, Eigen::Vector3d::Zero(), *ray) : std::nullopt;
    const auto uv =
        hit ? projector.Project(module.projector_from_camera * hit->point) : std::nullopt;
    if (!uv) {
      ++out.wrong;
      continue;
    }
    // Inverse of ElementCentre: u = offset_u + (c + 0.5) · pitch − 0.5.
    const int c = static_cast<int>(
        std::lround((uv->x() - layout.offset_px.x() + 0.5) / layout.pitch_px - 0.5));
    const int r = static_cast<int>(
        std::lround((uv->y() - layout.offset_px.y() + 0.5) / layout.pitch_px - 0.5));
    if (mod(r, pattern.rows) != o.row_mod || mod(c, pattern.cols) != o.col_mod) ++out.wrong;
  }
  ::testing::Test::RecordProperty("spots", out.spots);
  ::testing::Test::RecordProperty("decoded", out.decoded);
  ::testing::Test::RecordProperty("wrong", out.wrong);
  return out;
}

TEST(Decoder, PlaneAt90mmDecodesTheTruePositions) {
  Scene plane;
  plane.distance_mm = 90.0;
  const Outcome o = DecodeRender(testing::SmallDefaultModule(648), plane, 1);
  EXPECT_GT(o.decoded, 0.95 * o.spots);
  EXPECT_EQ(o.wrong, 0);
}

TEST(Decoder, Dn300CylinderDecodesTheTruePositions) {
  Scene cylinder;
  cylinder.type = Scene::Type::kCylinder;
  cylinder.diameter_mm = 300.0;
  cylinder.axis_point_mm = {8.0, 0.0, -10.0};
  const Outcome o = DecodeRender(testing::SmallDefaultModule(648), cylinder, 2);
  EXPECT_GT(o.decoded, 0.93 * o.spots);
  EXPECT_EQ(o.wrong, 0);
}

// A projector set a little in front of or behind the camera (a calibrated module is never
// exactly coplanar) shifts spots along v with depth too: the lattice bends with it.
TEST(Decoder, ProjectorOffsetAlongTheOpticalAxisDecodesTheTruePositions) {
  Scene plane;
  plane.distance_mm = 150.0;
  for (const double dz : {0.5, 5.0}) {
    ModuleDescription module = testing::SmallDefaultModule(648);
    module.projector_from_camera.translation.z() += dz;
    const Outcome o = DecodeRender(module, plane, 3);
    EXPECT_GT(o.decoded, 0.95 * o.spots) << dz;
    EXPECT_EQ(o.wrong, 0) << dz;
  }
}

// Thresholds are relative to the image's range: 12-bit captures and 8-bit levels stretched over
// the full 16-bit range decode like 8-bit ones (they used to give nothing: a 4-level contrast
// floor is noise at 12 bits).
TEST(Decoder, TwelveAndSixteenBitCapturesDecodeLikeEightBit) {
  Scene plane;
  plane.distance_mm = 90.0;
  const ModuleDescription module = testing::SmallDefaultModule(648);
  const Outcome eight = DecodeRender(module, plane, 1);
  const Outcome twelve = DecodeRender(module, plane, 1, 12);
  const Outcome sixteen = DecodeRender(module, plane, 1, 8, 257.0);
  EXPECT_GT(twelve.decoded, 0.95 * eight.decoded);
  EXPECT_GT(sixteen.decoded, 0.95 * eight.decoded);
  EXPECT_EQ(twelve.wrong, 0);
  EXPECT_EQ(sixteen.wrong, 0);
}

// Vitrified clay under the `paper` profile: dark glaze (the pattern's spots a few grey levels
// above black, scattered by a real projector's 0.6 px) round a DN300 wall seen from off its
// axis, as the runs see it. Every frame must keep one lattice: a group grown from a poorly
// supported seed (a border spot) inherited a row step sheared by half a column, which every
// other row still fits, and a run's frame lost half its spots (issue 17, clay_slip m0 8). The
// frames are rendered without supersampling (four times faster, the spots a little rougher).
// Before seeds were taken where the spots are densest, two of these eight frames broke: 57
// contradicting edges and 5 wrong positions, four groups and 13 wrong.
TEST(Decoder, DarkClayFramesKeepOneLattice) {
  const ModuleDescription module = testing::SmallDefaultModule(648);
  const SpotErrors paper = AtCameraWidth(*RealismProfile("paper"), module.camera.width);
  for (int trial = 0; trial < 8; ++trial) {
    Scene clay;
    clay.type = Scene::Type::kCylinder;
    clay.diameter_mm = 300.0;
    clay.material = Material::kVitrifiedClay;
    clay.material_seed = 1 + trial;
    clay.axis_point_mm = {6.0 * (trial % 3 - 1), 0.0, 4.0 * trial - 10.0};
    const Outcome o = DecodeRender(module, clay, 40 + trial, 8, 1.0, paper, 1);
    EXPECT_GT(o.decoded, 0.95 * o.spots) << "trial " << trial;
    EXPECT_GT(o.largest_group, 0.98 * o.spots) << "trial " << trial;
    EXPECT_LT(o.conflicts, 0.01 * o.spots) << "trial " << trial;
    // One lone spot in a dark corner (one neighbour within four pitches) can take a chance
    // decode from windows that show two or three of their lit elements; its epipolar line
    // then drops it in triangulation (measured: no point there).
    EXPECT_LE(o.wrong, 1) << "trial " << trial;
  }
}

}  // namespace
}  // namespace sewer3d
