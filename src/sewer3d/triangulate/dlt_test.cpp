#include "sewer3d/triangulate/dlt.hpp"

#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <random>

#include "sewer3d/camera/default_module.hpp"

namespace sewer3d {
namespace {

TEST(Dlt, ExactWithoutNoiseAcrossTheWorkingRange) {
  const ModuleDescription m = MakeDefaultModule({});
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> xy(-0.6, 0.6), z(75.0, 225.0);
  for (int i = 0; i < 1000; ++i) {
    const double depth = z(rng);
    const Eigen::Vector3d p(xy(rng) * depth, (xy(rng) + 0.25) * depth, depth);
    const Eigen::Vector3d q = m.projector_from_camera * p;
    const auto x =
        TriangulateDlt(p.head<2>() / p.z(), q.head<2>() / q.z(), m.projector_from_camera);
    ASSERT_TRUE(x.has_value());
    EXPECT_LT((*x - p).norm(), 1e-9 * depth);
  }
}

TEST(Dlt, DepthNoiseFollowsTheStereoGeometry) {
  // 0.1 px of noise on both images: depth error ≈ z² / (f b) · σ_d with σ_d the disparity
  // noise (√2 · 0.1 px along the baseline) — 0.024 mm at 150 mm.
  const ModuleDescription m = MakeDefaultModule({});
  const double f = m.camera.fx, b = m.projector_from_camera.translation.norm();
  std::mt19937 rng(2);
  std::normal_distribution<double> noise(0.0, 0.1 / f);
  double sum2 = 0.0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d p(10.0, 40.0, 150.0);
    const Eigen::Vector3d q = m.projector_from_camera * p;
    const Eigen::Vector2d c = p.head<2>() / p.z() + Eigen::Vector2d(noise(rng), noise(rng));
    const Eigen::Vector2d d = q.head<2>() / q.z() + Eigen::Vector2d(noise(rng), noise(rng));
    const auto x = TriangulateDlt(c, d, m.projector_from_camera);
    ASSERT_TRUE(x.has_value());
    sum2 += std::pow(x->z() - p.z(), 2);
  }
  const double rms = std::sqrt(sum2 / n);
  const double predicted = 150.0 * 150.0 / (f * b) * std::sqrt(2.0) * 0.1;
  EXPECT_NEAR(rms, predicted, 0.15 * predicted);
}

TEST(Dlt, SameAnswerAsTheSvdOfTheDltMatrix) {
  // Reference: the right singular vector of the smallest singular value by Jacobi SVD, with
  // a pixel of noise so that A has no exact null vector.
  const ModuleDescription m = MakeDefaultModule({});
  const Eigen::Matrix3d r = m.projector_from_camera.RotationMatrix();
  const Eigen::Vector3d t = m.projector_from_camera.translation;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> xy(-0.6, 0.6), z(75.0, 225.0);
  std::normal_distribution<double> noise(0.0, 1.0 / m.camera.fx);
  for (int i = 0; i < 500; ++i) {
    const double depth = z(rng);
    const Eigen::Vector3d p(xy(rng) * depth, (xy(rng) + 0.25) * depth, depth);
    const Eigen::Vector3d q = r * p + t;
    const Eigen::Vector2d c = p.head<2>() / p.z() + Eigen::Vector2d(noise(rng), noise(rng));
    const Eigen::Vector2d d = q.head<2>() / q.z() + Eigen::Vector2d(noise(rng), noise(rng));
    Eigen::Matrix4d a;
    a.row(0) << -1.0, 0.0, c.x(), 0.0;
    a.row(1) << 0.0, -1.0, c.y(), 0.0;
    a.row(2) << d.x() * r.row(2) - r.row(0), d.x() * t.z() - t.x();
    a.row(3) << d.y() * r.row(2) - r.row(1), d.y() * t.z() - t.y();
    for (int k = 0; k < 4; ++k) a.row(k).normalize();
    const Eigen::JacobiSVD<Eigen::Matrix4d> svd(a, Eigen::ComputeFullV);
    const Eigen::Vector4d v = svd.matrixV().col(3);
    const Eigen::Vector3d reference = v.head<3>() / v.w();
    const auto x = TriangulateDlt(c, d, m.projector_from_camera);
    ASSERT_TRUE(x.has_value());
    EXPECT_LT((*x - reference).norm(), 1e-9 * depth);
  }
}

TEST(Dlt, RejectsPointsBehindTheCamera) {
  const ModuleDescription m = MakeDefaultModule({});
  const Eigen::Vector3d p(5.0, 20.0, -100.0);
  const Eigen::Vector3d q = m.projector_from_camera * p;
  EXPECT_FALSE(TriangulateDlt(p.head<2>() / p.z(), q.head<2>() / q.z(), m.projector_from_camera));
}

TEST(OnProjectorRay, DepthIgnoresCameraErrorAcrossTheEpipolarLine) {
  // A projector 2 mm in front of the camera tilts the epipolar lines. A camera spot 0.3 px
  // off the element's epipolar line keeps its depth; the DLT moves the point along the ray.
  ModuleDescription m = MakeDefaultModule({});
  m.projector_from_camera.translation.z() += 2.0;
  Eigen::Matrix<double, 3, 4> p_projector;
  p_projector << m.projector_from_camera.RotationMatrix(), m.projector_from_camera.translation;
  const double f = m.camera.fx;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> xy(-0.6, 0.6), z(75.0, 225.0);
  double dlt_worst_mm = 0.0;
  for (int i = 0; i < 200; ++i) {
    const double depth = z(rng);
    const Eigen::Vector3d p(xy(rng) * depth, (xy(rng) + 0.25) * depth, depth);
    const Eigen::Vector3d q = m.projector_from_camera * p;
    const Eigen::Vector2d camera = p.head<2>() / p.z(), projector = q.head<2>() / q.z();
    const auto exact = TriangulateOnProjectorRay(camera, projector, p_projector);
    ASSERT_TRUE(exact.has_value());
    EXPECT_LT((*exact - p).norm(), 1e-9 * depth);
    // The element's epipolar line in the camera image runs along D_xy − x D_z, D the
    // projector ray's direction in the camera frame.
    const Eigen::Vector3d ray = m.projector_from_camera.rotation.conjugate() * q;
    const Eigen::Vector2d along = ray.head<2>() - camera * ray.z();
    const Eigen::Vector2d across = Eigen::Vector2d(-along.y(), along.x()).normalized();
    const Eigen::Vector2d camera_off = camera + 0.3 / f * across;
    const auto off_line = TriangulateOnProjectorRay(camera_off, projector, p_projector);
    ASSERT_TRUE(off_line.has_value());
    EXPECT_LT(std::abs(off_line->z() - depth), 1e-3) << depth;
    const auto dlt = TriangulateDlt(camera_off, projector, p_projector);
    ASSERT_TRUE(dlt.has_value());
    dlt_worst_mm = std::max(dlt_worst_mm, std::abs(dlt->z() - depth));
  }
  EXPECT_GT(dlt_worst_mm, 0.1);  // what the move onto the line removes
}

}  // namespace
}  // namespace sewer3d
