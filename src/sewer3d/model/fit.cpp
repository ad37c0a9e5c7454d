#include "sewer3d/model/fit.hpp"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

// Distance of x to the axis (point c, unit direction a) minus r.
struct CylinderResidual {
  explicit CylinderResidual(const Eigen::Vector3d& x) : x_(x) {}
  template <typename T>
  bool operator()(const T* c, const T* a, const T* r, T* residual) const {
    const Eigen::Matrix<T, 3, 1> d = x_.cast<T>() - Eigen::Map<const Eigen::Matrix<T, 3, 1>>(c);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> axis(a);
    const Eigen::Matrix<T, 3, 1> radial = d - d.dot(axis) * axis;
    residual[0] = sqrt(radial.squaredNorm() + T(1e-18)) - r[0];
    return true;
  }
  Eigen::Vector3d x_;
};

}  // namespace

std::optional<PlaneFit> FitPlane(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 3) return std::nullopt;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& p : points) scatter += (p - centroid) * (p - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  if (eig.eigenvalues()(1) <= 1e-12 * std::max(1.0, eig.eigenvalues()(2))) return std::nullopt;
  PlaneFit fit;
  fit.normal = eig.eigenvectors().col(0);
  if (fit.normal.z() > 0) fit.normal = -fit.normal;
  fit.offset = -fit.normal.dot(centroid);
  double sum2 = 0.0;
  for (const auto& p : points) {
    const double d = SignedDistance(fit, p);
    sum2 += d * d;
    fit.max_mm = std::max(fit.max_mm, std::abs(d));
  }
  fit.rms_mm = std::sqrt(sum2 / points.size());
  return fit;
}

double SignedDistance(const PlaneFit& plane, const Eigen::Vector3d& point) {
  return -(plane.normal.dot(point) + plane.offset);  // the normal points toward the camera
}

double SignedDistance(const CylinderFit& cylinder, const Eigen::Vector3d& point) {
  const Eigen::Vector3d d = point - cylinder.axis_point;
  const Eigen::Vector3d across = d - d.dot(cylinder.axis_direction) * cylinder.axis_direction;
  return across.norm() - cylinder.radius_mm;
}

std::optional<CylinderFit> FitCylinder(const std::vector<Eigen::Vector3d>& points,
                                       const Eigen::Vector3d& axis_guess) {
  if (points.size() < 6) return std::nullopt;
  const Eigen::Vector3d a0 = axis_guess.normalized();
  // Algebraic circle fit (Kåsa) of the points projected on the plane perpendicular to a0:
  // x² + y² + D x + E y + F = 0, linear least squares.
  const Eigen::Vector3d e1 = a0.unitOrthogonal(), e2 = a0.cross(e1);
  Eigen::MatrixXd m(points.size(), 3);
  Eigen::VectorXd rhs(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const double x = points[i].dot(e1), y = points[i].dot(e2);
    m.row(i) << x, y, 1.0;
    rhs(i) = -(x * x + y * y);
  }
  // Identical or collinear points (a line seen across the axis) fix no circle: the projected
  // points must spread in both directions of the cross-section.
  const Eigen::Vector2d mean = m.leftCols<2>().colwise().mean();
  const Eigen::MatrixX2d centred = m.leftCols<2>().rowwise() - mean.transpose();
  const Eigen::Matrix2d spread = centred.transpose() * centred / static_cast<double>(points.size());
  const Eigen::Vector2d extent =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(spread).eigenvalues();
  if (!(extent(0) > 1e-9 * extent(1) && extent(0) > 1e-12)) return std::nullopt;
  const auto qr = m.colPivHouseholderQr();
  if (qr.rank() < 3) return std::nullopt;
  const Eigen::Vector3d def = qr.solve(rhs);
  const double cx = -def(0) / 2, cy = -def(1) / 2;
  const double r2 = cx * cx + cy * cy - def(2);
  if (!(r2 > 0.0) || !std::isfinite(r2)) return std::nullopt;
  Eigen::Vector3d c = cx * e1 + cy * e2, a = a0;
  double r = std::sqrt(r2);
  ceres::Problem problem;
  for (const auto& p : points) {
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<CylinderResidual, 1, 3, 3, 1>(new CylinderResidual(p)),
        nullptr, c.data(), a.data(), &r);
  }
  problem.SetManifold(a.data(), new ceres::SphereManifold<3>());
  ceres::Solver::Options options;
  options.max_num_iterations = 100;
  options.function_tolerance = 1e-14;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-14;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  CylinderFit fit;
  fit.axis_direction = a.normalized();
  fit.axis_point = c - c.dot(fit.axis_direction) * fit.axis_direction;  // closest to the origin
  fit.radius_mm = r;
  fit.converged = summary.IsSolutionUsable();
  double sum2 = 0.0;
  for (const auto& p : points) {
    const double e = SignedDistance(fit, p);
    sum2 += e * e;
    fit.max_mm = std::max(fit.max_mm, std::abs(e));
  }
  fit.rms_mm = std::sqrt(sum2 / points.size());
  if (const auto plane = FitPlane(points)) {
    fit.plane_rms_mm = plane->rms_mm;
    fit.flat = plane->rms_mm <= fit.rms_mm;
  }
  return fit;
}

std::optional<CylinderFit> FitCylinderAnyAxis(const std::vector<Eigen::Vector3d>& points) {
  std::optional<CylinderFit> best;
  for (const Eigen::Vector3d axis :
       {Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ()}) {
    auto fit = FitCylinder(points, axis);
    if (fit && fit->converged && (!best || fit->rms_mm < best->rms_mm)) best = std::move(fit);
  }
  return best ? best : FitCylinder(points, Eigen::Vector3d::UnitY());
}

std::vector<Eigen::Vector3d> InnerPoints(const std::vector<Eigen::Vector3d>& points,
                                         double fraction) {
  SEWER3D_VALIDATE(fraction > 0.0 && fraction <= 1.0, "inner_fraction",
                   "must be > 0 and <= 1, got " << fraction);
  if (fraction == 1.0) {  // no bounds to round at the extremes
    std::vector<Eigen::Vector3d> front;
    for (const auto& p : points)
      if (p.z() > 0) front.push_back(p);
    return front;
  }
  double x_lo = 1e300, x_hi = -1e300, y_lo = 1e300, y_hi = -1e300;
  for (const auto& p : points) {
    if (!(p.z() > 0)) continue;
    x_lo = std::min(x_lo, p.x() / p.z()), x_hi = std::max(x_hi, p.x() / p.z());
    y_lo = std::min(y_lo, p.y() / p.z()), y_hi = std::max(y_hi, p.y() / p.z());
  }
  const double mx = 0.5 * (x_lo + x_hi), my = 0.5 * (y_lo + y_hi);
  const double hx = 0.5 * fraction * (x_hi - x_lo), hy = 0.5 * fraction * (y_hi - y_lo);
  std::vector<Eigen::Vector3d> inner;
  for (const auto& p : points) {
    if (p.z() > 0 && std::abs(p.x() / p.z() - mx) <= hx && std::abs(p.y() / p.z() - my) <= hy)
      inner.push_back(p);
  }
  return inner;
}

}  // namespace sewer3d
