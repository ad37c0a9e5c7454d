#pragma once
/// \file
/// Extreme eigenvalues of the certificate matrix S = Q − Diag(Λ) (lifted_cost.hpp): dense for
/// small graphs, Lanczos (Spectra) on the operator otherwise. Used for the tolerance scale and
/// for the staircase's climbing direction; whether S is positive semidefinite is decided by a
/// factorisation (RotationForm::IsPositiveDefinite), since Lanczos can miss an eigenvalue.

#include <Eigen/Core>

#include "sewer3d/posegraph/lifted_cost.hpp"

namespace sewer3d::lifted {

struct Eigenpair {
  double value = 0.0;
  Eigen::VectorXd vector;
  bool converged = false;
  int restarts = 0;  ///< Lanczos restarts
};

/// |λ|_max(S), the scale of the certificate's tolerances (a lower estimate by power iteration
/// if Lanczos does not converge).
double LargestEigenvalueMagnitude(const RotationForm& form, const MultiplierBlocks& lambda);

/// λ_min(S) and its eigenvector: dense for small graphs; else Lanczos for the dominant
/// eigenvalue of S − largest·I, which is λ_min − largest. Attempt 0 starts Lanczos from
/// Spectra's default vector, later attempts from random ones.
Eigenpair MinimumEigenpair(const RotationForm& form, const MultiplierBlocks& lambda, int attempt,
                           double largest);

}  // namespace sewer3d::lifted
