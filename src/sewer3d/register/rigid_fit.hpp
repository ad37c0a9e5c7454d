#pragma once
/// \file
/// Closed-form rigid fits between corresponding 3-D points (paper §4.3, feature-based
/// registration): the minimal 3-point solver RANSAC draws from, and the weighted least-squares
/// fit (Umeyama 1991 without scale; equivalently Arun/Kabsch via the SVD) on the inliers.
/// Both return dst_from_src: dst_i ≈ R src_i + t.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "sewer3d/core/rigid3.hpp"

namespace sewer3d {

/// The rigid transform that maps the triangle src[0..2] onto dst[0..2]: an orthonormal frame
/// is built on each triangle (origin at its centroid, x toward vertex 0, z its normal) and
/// R = F_dst F_srcᵀ, t = c_dst − R c_src. Exact for noise-free congruent triangles; with noise
/// it is one of many reasonable minimal estimates (RANSAC only scores it). nullopt when either
/// triangle is degenerate (an edge or the doubled area below `min_size_mm` mm / mm²).
std::optional<Rigid3d> RigidFromThreePoints(const Eigen::Vector3d src[3],
                                            const Eigen::Vector3d dst[3],
                                            double min_size_mm = 1e-6);

/// Least-squares rigid fit minimising Σ w_i |dst_i − (R src_i + t)|² (Umeyama 1991, scale
/// fixed to 1): R from the SVD of the weighted cross-covariance with the reflection fixed
/// (det R = +1). `weights` empty means all 1. nullopt with fewer than 3 points, non-positive
/// total weight, or points that are collinear (rank < 2 of the cross-covariance).
std::optional<Rigid3d> UmeyamaFit(const std::vector<Eigen::Vector3d>& src,
                                  const std::vector<Eigen::Vector3d>& dst,
                                  const std::vector<double>& weights = {});

}  // namespace sewer3d
