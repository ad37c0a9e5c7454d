// Initial poses from a synthetic odometry, the carrier offset from six walls, and the neighbour
// search over a six-module rig (648 × 486 cameras) in a DN300 pipe.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "sewer3d/register/initial_poses.hpp"
#include "sewer3d/register/neighbours.hpp"
#include "sewer3d/sim/rig.hpp"
#include "sewer3d/testing/matchers.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

constexpr double kSpeed = 100.0;  // mm/s
constexpr double kPeriod = 0.5;   // s between a module's acquisitions: 50 mm of travel
constexpr double kScale = 1.004;  // the cable counter's scale error
constexpr int kCounters = 6;

// A run of kCounters acquisitions per module; odd modules 20 ms later; odometry at 20 Hz.
CaptureRun SyntheticRun() {
  CaptureRun run;
  run.rig = MakeRig(testing::SmallDefaultModule(648), RigOptions{});
  for (int j = 0; j < kCounters; ++j) {
    for (int m = 0; m < 6; ++m) {
      const double t = 0.1 + kPeriod * j + (m % 2 == 1 ? 0.02 : 0.0);
      for (ImageKind kind : kImageKinds) {
        RunImage image;
        image.module = m;
        image.counter = j;
        image.kind = kind;
        image.time_s = t + 0.005 * (static_cast<int>(kind) - 1);
        run.images.push_back(image);
      }
    }
  }
  std::sort(run.images.begin(), run.images.end(),
            [](const RunImage& a, const RunImage& b) { return a.time_s < b.time_s; });
  for (int k = 0; k <= 80; ++k)
    run.odometry.push_back({0.05 * k, 7.0 + kScale * kSpeed * 0.05 * k});
  return run;
}

TEST(InitialPoses, CarrierMovesAlongModelZByTheOdometryDistance) {
  const CaptureRun run = SyntheticRun();
  const InitialPosesResult r = InitialPoses(run);
  ASSERT_EQ(r.report.nodes, 6 * kCounters);
  EXPECT_EQ(r.report.without_pattern, 0);
  EXPECT_EQ(r.report.outside_odometry, 0);
  const double t0 = 0.1 - 0.005;  // the first image: module 0's texture_before
  EXPECT_DOUBLE_EQ(r.report.first_image_time_s, t0);
  for (const AcquisitionNode& n : r.nodes) {
    const double d = kScale * kSpeed * (n.time_s - t0);
    EXPECT_NEAR(n.distance_mm, d, 1e-9);
    const Rigid3d expected = Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, d)) *
                             run.rig.modules[n.module].carrier_from_camera;
    EXPECT_THAT(n.world_from_camera, testing::PoseNear(expected, 1e-9, 1e-9));
  }
  CaptureRun missing = run;
  missing.images.erase(
      std::find_if(missing.images.begin(), missing.images.end(),
                   [](const RunImage& i) { return i.kind == ImageKind::kPattern; }));
  EXPECT_EQ(InitialPoses(missing).report.without_pattern, 1);
  missing.odometry.clear();
  EXPECT_THROW(InitialPoses(missing), std::invalid_argument);
}

TEST(InitialPoses, CarrierOffsetFromSixWalls) {
  const Rig rig = MakeRig(testing::SmallDefaultModule(648), RigOptions{});
  const Eigen::Vector2d axis(-10.0, -15.0);  // carrier 10 mm right of and 15 mm below the axis
  const double radius = 150.0;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<ModuleWallPoints> walls;
  for (int m = 0; m < 6; ++m) {
    const CameraModel camera(rig.modules[m].module.camera);
    const Rigid3d& carrier_from_camera = rig.modules[m].carrier_from_camera;
    ModuleWallPoints wall{m, {}};
    for (int v = 20; v < 486; v += 40) {
      for (int u = 20; u < 648; u += 40) {
        const Eigen::Vector3d d = carrier_from_camera.rotation * *camera.Ray(Eigen::Vector2d(u, v));
        const Eigen::Vector2d q = carrier_from_camera.translation.head<2>() - axis;
        const Eigen::Vector2d e = d.head<2>();
        const double b = q.dot(e), c = q.squaredNorm() - radius * radius;
        const double s = (-b + std::sqrt(b * b - e.squaredNorm() * c)) / e.squaredNorm();
        const Eigen::Vector3d p =
            carrier_from_camera.Inverse() * (carrier_from_camera.translation + s * d);
        wall.points_in_camera.push_back(p * (1.0 + noise(rng) / p.norm()));
      }
    }
    walls.push_back(wall);
  }
  const CarrierOffsetEstimate e = EstimateCarrierOffset(rig, walls);
  ASSERT_TRUE(e.valid);
  EXPECT_EQ(e.modules, 6);
  EXPECT_LT((e.axis_in_carrier_mm - axis).norm(), 0.05);
  EXPECT_NEAR(e.diameter_mm, 300.0, 0.05);
  EXPECT_LT(e.rms_mm, 0.1);
  EXPECT_GT(e.inlier_fraction, 0.99);
  // An intrusion in module 0's view: the points of its upper half 3 mm inward (within the
  // 5 mm band of the inlier share). The robust fit leaves them out; least squares lets them
  // pull the centre.
  std::vector<ModuleWallPoints> intruded = walls;
  std::vector<Eigen::Vector3d>& points = intruded[0].points_in_camera;
  for (size_t i = 0; i < points.size() / 2; ++i) points[i] *= 1.0 - 3.0 / points[i].norm();
  const CarrierOffsetEstimate trimmed = EstimateCarrierOffset(rig, intruded);
  CarrierOffsetOptions untrimmed_options;
  untrimmed_options.circle.tukey_c = 1e6;  // every point weighs alike: least squares
  const CarrierOffsetEstimate untrimmed = EstimateCarrierOffset(rig, intruded, untrimmed_options);
  EXPECT_LT((trimmed.axis_in_carrier_mm - axis).norm(), 0.05);
  EXPECT_NEAR(trimmed.inlier_fraction, 11.0 / 12.0, 0.02);  // 6 × 12 × 16 points, 96 moved
  EXPECT_GT((untrimmed.axis_in_carrier_mm - axis).norm(), 0.2);
  walls.resize(2);
  EXPECT_FALSE(EstimateCarrierOffset(rig, walls).valid);  // two modules: too narrow an arc
}

TEST(Neighbours, FindsAlongAndAroundPairsAndRejectsFarOnes) {
  const CaptureRun run = SyntheticRun();
  const std::vector<AcquisitionNode> nodes = InitialPoses(run).nodes;
  NeighbourOptions options;
  options.max_counter_gap = kCounters;  // let the overlap decide along the pipe
  const NeighbourResult r = FindNeighbours(nodes, run.rig, options);
  EXPECT_EQ(r.report.nodes_without_wall, 0);
  std::map<std::pair<int, int>, double> along;  // (module, counter gap) → min overlap
  int around = 0;
  for (const NeighbourPair& p : r.pairs) {
    const AcquisitionNode &a = nodes[p.a], &b = nodes[p.b];
    if (p.kind == PairKind::kAlong) {
      EXPECT_EQ(a.module, b.module);
      const auto key = std::make_pair(a.module, std::abs(a.counter - b.counter));
      along[key] = along.count(key) ? std::min(along[key], p.Overlap()) : p.Overlap();
    } else {
      const int d = (a.module - b.module + 6) % 6;
      EXPECT_TRUE(d == 1 || d == 5) << a.module << " " << b.module;
      ++around;
    }
    RecordProperty("pair_" + std::to_string(p.a) + "_" + std::to_string(p.b),
                   std::string(PairKindName(p.kind)) + " " + std::to_string(p.overlap_ab) + " " +
                       std::to_string(p.overlap_ba));
  }
  for (int m = 0; m < 6; ++m) {
    const auto one = std::make_pair(m, 1), four = std::make_pair(m, 4);
    ASSERT_TRUE(along.count(one)) << "module " << m;
    EXPECT_GT(along[one], 0.5);  // 50 mm steps over a ≈ 170 mm footprint
    EXPECT_FALSE(along.count(four)) << "200 mm apart: no overlap";
  }
  EXPECT_GE(around, 6 * (kCounters - 1));
  EXPECT_GT(r.report.rejected_overlap, 0);
}

}  // namespace
}  // namespace sewer3d
