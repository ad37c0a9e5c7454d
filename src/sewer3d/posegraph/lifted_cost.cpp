#include "sewer3d/posegraph/lifted_cost.hpp"

#include <Eigen/Eigenvalues>

namespace sewer3d::lifted {
namespace {

using Eigen::MatrixXd;

Eigen::Matrix3d Sym(const Eigen::Matrix3d& m) { return 0.5 * (m + m.transpose()); }

}  // namespace

MatrixXd Project(const MatrixXd& x, const MatrixXd& v) {
  MatrixXd out = v;
  for (Eigen::Index i = 0; i < x.rows(); i += 3) {
    const auto xi = x.middleRows<3>(i);
    out.middleRows<3>(i) -= Sym(v.middleRows<3>(i) * xi.transpose()) * xi;
  }
  return out;
}

MatrixXd Retract(const MatrixXd& x, const MatrixXd& v) {
  MatrixXd out = x + v;
  for (Eigen::Index i = 0; i < x.rows(); i += 3) {
    const Eigen::Matrix3d zz = out.middleRows<3>(i) * out.middleRows<3>(i).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(zz);
    const Eigen::Matrix3d inverse_root = es.eigenvectors() *
                                         es.eigenvalues().cwiseSqrt().cwiseInverse().asDiagonal() *
                                         es.eigenvectors().transpose();
    out.middleRows<3>(i) = inverse_root * out.middleRows<3>(i);
  }
  return out;
}

MultiplierBlocks Multipliers(const MatrixXd& x, const MatrixXd& qx) {
  MultiplierBlocks lambda(x.rows() / 3);
  for (size_t i = 0; i < lambda.size(); ++i) {
    lambda[i] = Sym(qx.middleRows<3>(3 * i) * x.middleRows<3>(3 * i).transpose());
  }
  return lambda;
}

MatrixXd CertificateProduct(const RotationForm& form, const MultiplierBlocks& lambda,
                            const MatrixXd& v) {
  MatrixXd out = form.Apply(v);
  for (size_t i = 0; i < lambda.size(); ++i)
    out.middleRows<3>(3 * i) -= lambda[i] * v.middleRows<3>(3 * i);
  return out;
}

double Inner(const MatrixXd& a, const MatrixXd& b) { return a.cwiseProduct(b).sum(); }

Point::Point(const RotationForm& form, MatrixXd at) : x(std::move(at)), qx(form.Apply(x)) {
  lambda = Multipliers(x, qx);
  gradient = 2.0 * qx;
  for (size_t i = 0; i < lambda.size(); ++i)
    gradient.middleRows<3>(3 * i) -= 2.0 * lambda[i] * x.middleRows<3>(3 * i);
  cost = form.Cost(x, qx);
}

MatrixXd Point::Hessian(const RotationForm& form, const MatrixXd& v) const {
  return 2.0 * Project(x, CertificateProduct(form, lambda, v));
}

}  // namespace sewer3d::lifted
