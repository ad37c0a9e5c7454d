#pragma once
/// \file
/// The smooth part of the wall, ring by ring: a robust fit of the displacement around each row
/// of the coarse map to a0 + c1 cos θ + s1 sin θ + c2 cos 2θ + s2 sin 2θ (mean radius change,
/// axis offset, ovality), so that intrusions, deposits and spalling stand out as residuals and
/// deformation is read from the 2θ terms (docs/inspection.md).

#include <Eigen/Core>
#include <vector>

#include "sewer3d/inspect/coarse_map.hpp"

namespace sewer3d {

using RingCoefficients = Eigen::Matrix<double, 5, 1>;  ///< a0, c1, s1, c2, s2 (mm)

/// The ring model's value at clock angle `theta_rad`.
double RingValue(const RingCoefficients& k, double theta_rad);

struct RingFit {
  RingCoefficients k = RingCoefficients::Zero();
  double coverage = 0.0;  ///< share of the row's columns with a value
  bool valid = false;     ///< coverage ≥ min_coverage and the fit converged
};

/// A robust (Tukey biweight, scale from the MAD, started at the median) least-squares fit of
/// `values` at angles `theta_rad` to a0 + Σ_{k ≤ order} (c_k cos kθ + s_k sin kθ), order 1 or 2;
/// returns (a0, c1, s1[, c2, s2]), empty when there are fewer values than 2 · (2 order + 1).
Eigen::VectorXd RobustHarmonicFit(const std::vector<double>& theta_rad,
                                  const std::vector<double>& values, int order);

/// One robust (Tukey, scale from the MAD) ring fit per row of `map`. Rows measured over less
/// than `min_coverage` of the turn but at least a third take the 2θ terms of the nearest fully
/// fitted row (within 300 mm) and fit the rest; rows with less are not valid (their k holds
/// only a0, the median).
std::vector<RingFit> FitRings(const CoarseMap& map, double min_coverage);

/// A stretch of coarse rows [begin, end) that belongs to one pipe section.
struct RowRange {
  int begin = 0;
  int end = 0;
};

/// The wall's smooth shape per row: within each section, the running median (± half_rows) of
/// the valid rows' coefficients around the row, or around the nearest valid row when that is
/// within ± half_rows; other rows, and rows outside every section, get NaN coefficients.
std::vector<RingCoefficients> SmoothRings(const std::vector<RingFit>& fits,
                                          const std::vector<RowRange>& sections, int half_rows);

/// `map` minus the ring model of each row (NaN where either is missing).
cv::Mat1f RingResidual(const CoarseMap& map, const std::vector<RingCoefficients>& rings);

/// Robust standard deviation (1.4826 · MAD around the median) of the finite values of `m`;
/// 0 when there are none.
double RobustSigma(const cv::Mat1f& m);

}  // namespace sewer3d
