#include "sewer3d/posegraph/certificate_eigen.hpp"

#include <Spectra/SymEigsSolver.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

namespace sewer3d::lifted {
namespace {

using Eigen::MatrixXd;

/// Spectra's relative convergence tolerance.
constexpr double kLanczosTolerance = 1e-12;

/// Graphs up to this many nodes get a dense eigendecomposition of S (3n × 3n).
constexpr int kDenseNodes = 300;

/// y = (S + shift·I) x for Spectra.
class CertificateOperator {
 public:
  using Scalar = double;
  CertificateOperator(const RotationForm& form, const MultiplierBlocks& lambda, double shift)
      : form_(form), lambda_(lambda), shift_(shift) {}
  Eigen::Index rows() const { return 3 * form_.NodeCount(); }
  Eigen::Index cols() const { return rows(); }
  void perform_op(const double* in, double* out) const {
    const Eigen::Map<const Eigen::VectorXd> x(in, rows());
    Eigen::Map<Eigen::VectorXd> y(out, rows());
    y = CertificateProduct(form_, lambda_, x) + shift_ * x;
  }

 private:
  const RotationForm& form_;
  const MultiplierBlocks& lambda_;
  double shift_;
};

/// Attempt 0 starts Lanczos from Spectra's default vector, later attempts from random ones.
Eigenpair DominantEigenpair(const RotationForm& form, const MultiplierBlocks& lambda, double shift,
                            int attempt) {
  CertificateOperator op(form, lambda, shift);
  const int n = static_cast<int>(op.rows());
  Spectra::SymEigsSolver<CertificateOperator> solver(op, 1, std::min(n, 60));
  if (attempt == 0) {
    solver.init();
  } else {
    std::mt19937 rng(attempt);
    std::normal_distribution<double> normal;
    Eigen::VectorXd start(n);
    for (double& value : start) value = normal(rng);
    solver.init(start.data());
  }
  Eigenpair pair;
  solver.compute(Spectra::SortRule::LargestMagn, 5000, kLanczosTolerance);
  pair.restarts = static_cast<int>(solver.num_iterations());
  pair.converged = solver.info() == Spectra::CompInfo::Successful;
  if (pair.converged) {
    pair.value = solver.eigenvalues()(0) - shift;
    pair.vector = solver.eigenvectors().col(0);
  }
  return pair;
}

/// λ_min(S) by a dense eigendecomposition, for small graphs.
Eigenpair DenseMinimumEigenpair(const RotationForm& form, const MultiplierBlocks& lambda,
                                double* largest) {
  const int n = 3 * form.NodeCount();
  const MatrixXd s = CertificateProduct(form, lambda, MatrixXd::Identity(n, n));
  const Eigen::SelfAdjointEigenSolver<MatrixXd> es(0.5 * (s + s.transpose()));
  Eigenpair pair;
  pair.converged = es.info() == Eigen::Success;
  pair.value = es.eigenvalues()(0);
  pair.vector = es.eigenvectors().col(0);
  *largest = es.eigenvalues().cwiseAbs().maxCoeff();
  return pair;
}

}  // namespace

double LargestEigenvalueMagnitude(const RotationForm& form, const MultiplierBlocks& lambda) {
  if (form.NodeCount() <= kDenseNodes) {
    double largest = 0.0;
    DenseMinimumEigenpair(form, lambda, &largest);
    return largest;
  }
  const Eigenpair dominant = DominantEigenpair(form, lambda, 0.0, 0);
  if (dominant.converged) return std::abs(dominant.value);
  // Lanczos did not converge: power iteration gives a lower estimate, enough for tolerances.
  Eigen::VectorXd v = Eigen::VectorXd::Ones(3 * form.NodeCount()).normalized();
  double estimate = 0.0;
  for (int k = 0; k < 100; ++k) {
    const Eigen::VectorXd w = CertificateProduct(form, lambda, v);
    estimate = w.norm();
    if (!(estimate > 0.0)) break;
    v = w / estimate;
  }
  return estimate;
}

Eigenpair MinimumEigenpair(const RotationForm& form, const MultiplierBlocks& lambda, int attempt,
                           double largest) {
  double unused = 0.0;
  return form.NodeCount() <= kDenseNodes ? DenseMinimumEigenpair(form, lambda, &unused)
                                         : DominantEigenpair(form, lambda, -largest, attempt);
}

}  // namespace sewer3d::lifted
