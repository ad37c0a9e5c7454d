#pragma once
/// \file
/// Robust circle fit of one cross-section (paper §4.4 fits a cylinder; the model's centreline
/// fit, model/centreline_fit.hpp, fits one circle per slice; the registration one per instant
/// to the six modules' walls, register/initial_poses.hpp). Kåsa's algebraic centre, then a
/// least-median-of-squares start over angular sectors, then a geometric Gauss–Newton fit
/// iteratively reweighted with Tukey weights on a MAD scale, so that what is not round pipe
/// (intrusions, deposits, joint gaps, spalling) does not pull the centre.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace sewer3d {

struct CircleFitOptions {
  /// Also fit the elliptic term a·cos 2θ + b·sin 2θ of the radius, so that an oval pipe's
  /// wall is not taken for outliers. Only the centre and the mean radius are kept: the model
  /// stays a circle and ovality stays in the displacement.
  bool model_ovality = true;
  double min_scale_mm = 0.05;  ///< floor of the robust residual scale (noise-free data)
  double tukey_c = 4.685;      ///< Tukey cut-off in scales
  int lmeds_samples = 150;     ///< minimal subsets tried for the least-median start
  int iterations = 20;         ///< IRLS iterations at most

  void Check() const;
};

struct CircleFit {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius_mm = 0.0;      ///< mean radius (the circle)
  double ovality_mm = 0.0;     ///< amplitude √(a² + b²) of the 2θ term (0 unless modelled)
  double scale_mm = 0.0;       ///< robust residual scale (1.4826 · MAD, floored)
  double rms_mm = 0.0;         ///< RMS residual of the inliers
  double inlier_fraction = 0;  ///< points with a non-zero Tukey weight
  double coverage_deg = 0.0;   ///< angular extent of the inliers (36 bins of 10°)
  bool converged = false;      ///< usable: finite, with enough inliers (IRLS stops at |Δ| < 1e-7)
};

/// Fits `points` (2D, mm). Needs ≥ 8 points; fewer, or a degenerate configuration, gives
/// converged = false. `inliers`: if given, set to one flag per point (1: a non-zero Tukey
/// weight at the final parameters, the points of rms_mm and inlier_fraction).
CircleFit FitCircleRobust(const std::vector<Eigen::Vector2d>& points,
                          const CircleFitOptions& options,
                          std::vector<std::uint8_t>* inliers = nullptr);

}  // namespace sewer3d
