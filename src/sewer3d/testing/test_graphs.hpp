#pragma once
/// \file
/// Synthetic pose graphs for tests: random poses, perturbations, and a ring of
/// poses with odometry and loop closures measured from the truth.

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "sewer3d/core/units.hpp"
#include "sewer3d/posegraph/pose_graph.hpp"

namespace sewer3d::test_graphs {

/// N standard normal draws in a fixed order. C++ leaves the order in which a call's arguments
/// are evaluated unspecified (gcc goes last to first, clang first to last), so
/// `Vector3d(n(rng), n(rng), n(rng))` made other graphs in a clang build than in a gcc build;
/// these are drawn last to first, the order the tests' seeds were chosen with.
template <int N>
Eigen::Matrix<double, N, 1> Draws(std::normal_distribution<double>& n, std::mt19937& rng) {
  Eigen::Matrix<double, N, 1> v;
  for (int i = N - 1; i >= 0; --i) v(i) = n(rng);
  return v;
}

inline Rigid3d RandomPose(std::mt19937& rng, double spread_mm) {
  std::normal_distribution<double> n(0.0, 1.0);
  const Eigen::Vector4d q = Draws<4>(n, rng);
  const Eigen::Vector3d t = Draws<3>(n, rng);
  return {Eigen::Quaterniond(q(0), q(1), q(2), q(3)), t * spread_mm};
}

inline Rigid3d Perturb(const Rigid3d& pose, std::mt19937& rng, double rot_rad, double trans_mm) {
  std::normal_distribution<double> n(0.0, 1.0);
  const Eigen::Vector3d w = Draws<3>(n, rng) * rot_rad;
  const Eigen::Quaterniond dq(Eigen::AngleAxisd(w.norm(), w.normalized()));
  const Eigen::Vector3d t = Draws<3>(n, rng);
  return {pose.rotation * dq, pose.translation + t * trans_mm};
}

inline Matrix6d RandomInformation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Matrix6d a;
  for (int i = 0; i < 36; ++i) a(i) = n(rng);
  return a * a.transpose() + Matrix6d::Identity();
}

inline double RotationErrorDeg(const Rigid3d& a, const Rigid3d& b) {
  return RadToDeg(a.rotation.angularDistance(b.rotation));
}

/// Information diag(1, 1, 1, 400, 400, 400): 1 mm and about 3° standard deviations.
inline Matrix6d RingInformation(std::mt19937&) {
  Matrix6d information = Matrix6d::Identity();
  information.diagonal() << 1, 1, 1, 400, 400, 400;
  return information;
}

/// A ring of poses with odometry and a few loop closures, measured from `truth` with the given
/// noise; each edge's information from `information`.
inline PoseGraph RingGraph(
    const std::vector<Rigid3d>& truth, std::mt19937& rng, double rot_noise, double trans_noise,
    const std::function<Matrix6d(std::mt19937&)>& information = RingInformation) {
  PoseGraph graph;
  for (size_t i = 0; i < truth.size(); ++i) graph.SetNode(static_cast<int>(i), truth[i]);
  const int n = static_cast<int>(truth.size());
  auto add = [&](int a, int b) {
    PoseEdge e;
    e.from = a;
    e.to = b;
    e.a_from_b = Perturb(truth[a].Inverse() * truth[b], rng, rot_noise, trans_noise);
    e.information = information(rng);
    graph.AddEdge(e);
  };
  for (int i = 0; i + 1 < n; ++i) add(i, i + 1);
  for (int i = 0; i + 5 < n; i += 3) add(i, i + 5);
  add(n - 1, 0);
  return graph;
}

}  // namespace sewer3d::test_graphs
