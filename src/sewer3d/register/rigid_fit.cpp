#include "sewer3d/register/rigid_fit.hpp"

#include <Eigen/SVD>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

// Columns: unit x toward vertex 0 from the centroid, unit z the normal, y = z × x.
std::optional<Eigen::Matrix3d> TriangleFrame(const Eigen::Vector3d p[3], double min_size,
                                             Eigen::Vector3d* centroid) {
  *centroid = (p[0] + p[1] + p[2]) / 3.0;
  const Eigen::Vector3d normal = (p[1] - p[0]).cross(p[2] - p[0]);
  const Eigen::Vector3d x = p[0] - *centroid;
  if (normal.norm() < min_size || x.norm() < min_size) return std::nullopt;
  Eigen::Matrix3d f;
  f.col(0) = x.normalized();
  f.col(2) = normal.normalized();
  f.col(1) = f.col(2).cross(f.col(0));
  return f;
}

}  // namespace

std::optional<Rigid3d> RigidFromThreePoints(const Eigen::Vector3d src[3],
                                            const Eigen::Vector3d dst[3], double min_size_mm) {
  Eigen::Vector3d c_src, c_dst;
  const auto f_src = TriangleFrame(src, min_size_mm, &c_src);
  const auto f_dst = TriangleFrame(dst, min_size_mm, &c_dst);
  if (!f_src || !f_dst) return std::nullopt;
  const Eigen::Matrix3d r = *f_dst * f_src->transpose();
  return Rigid3d(r, c_dst - r * c_src);
}

std::optional<Rigid3d> UmeyamaFit(const std::vector<Eigen::Vector3d>& src,
                                  const std::vector<Eigen::Vector3d>& dst,
                                  const std::vector<double>& weights) {
  SEWER3D_CHECK(src.size() == dst.size());
  SEWER3D_CHECK(weights.empty() || weights.size() == src.size());
  const size_t n = src.size();
  if (n < 3) return std::nullopt;
  double w_sum = 0.0;
  Eigen::Vector3d c_src = Eigen::Vector3d::Zero(), c_dst = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < n; ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    w_sum += w;
    c_src += w * src[i];
    c_dst += w * dst[i];
  }
  if (!(w_sum > 0.0)) return std::nullopt;
  c_src /= w_sum;
  c_dst /= w_sum;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();  // Σ w (dst − c_dst)(src − c_src)ᵀ
  for (size_t i = 0; i < n; ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    cov += w * (dst[i] - c_dst) * (src[i] - c_src).transpose();
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d& s = svd.singularValues();
  if (!(s(1) > 1e-12 * std::max(1.0, s(0)))) return std::nullopt;  // collinear points
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0) d(2, 2) = -1.0;
  const Eigen::Matrix3d r = svd.matrixU() * d * svd.matrixV().transpose();
  return Rigid3d(r, c_dst - r * c_src);
}

}  // namespace sewer3d
