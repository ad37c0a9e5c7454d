#pragma once
/// \file
/// Small 3 × 3-block helpers shared by the posegraph solvers: sparse assembly of 3 × 3 blocks
/// and the nearest rotation to a 3 × 3 matrix.

#include <Eigen/Core>
#include <Eigen/SVD>
#include <Eigen/SparseCore>
#include <vector>

namespace sewer3d {

using Triplets = std::vector<Eigen::Triplet<double>>;

/// Appends the 3 × 3 block `m` with its top-left element at (row, col).
inline void AddBlock(Triplets& t, int row, int col, const Eigen::Matrix3d& m) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) t.emplace_back(row + r, col + c, m(r, c));
  }
}

/// The rotation nearest to `m` in the Frobenius norm (SVD, determinant forced to +1).
inline Eigen::Matrix3d ProjectToRotation(const Eigen::Matrix3d& m) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * d * svd.matrixV().transpose();
}

}  // namespace sewer3d
