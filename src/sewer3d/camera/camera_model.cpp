#include "sewer3d/camera/camera_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

// Largest undistorted radius considered: 84° off axis. Lenses of this product stay far inside.
constexpr double kMaxRadius = 10.0;

// d/dr [r (1 + k1 r² + k2 r⁴ + k3 r⁶)] = 1 + 3 k1 r² + 5 k2 r⁴ + 7 k3 r⁶.
double RadialSlope(const std::array<double, 3>& k, double r) {
  const double s = r * r;
  return 1.0 + s * (3.0 * k[0] + s * (5.0 * k[1] + s * 7.0 * k[2]));
}

// First positive root of the slope, or +inf when the map increases up to kMaxRadius.
double FindFoldRadius(const std::array<double, 3>& k) {
  constexpr int kSteps = 20000;
  double previous = 0.0;
  for (int i = 1; i <= kSteps; ++i) {
    const double r = kMaxRadius * i / kSteps;
    if (RadialSlope(k, r) <= 0.0) {
      double lo = previous, hi = r;  // slope(lo) > 0 >= slope(hi)
      for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
        const double mid = 0.5 * (lo + hi);
        (RadialSlope(k, mid) > 0.0 ? lo : hi) = mid;
      }
      return lo;
    }
    previous = r;
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace

void CameraIntrinsics::Check() const {
  // Field names as in module.json.
  SEWER3D_VALIDATE(width > 0, "width", "must be > 0, got " << width);
  SEWER3D_VALIDATE(height > 0, "height", "must be > 0, got " << height);
  SEWER3D_VALIDATE(std::isfinite(fx) && fx > 0.0, "fx", "must be finite and > 0, got " << fx);
  SEWER3D_VALIDATE(std::isfinite(fy) && fy > 0.0, "fy", "must be finite and > 0, got " << fy);
  SEWER3D_VALIDATE(std::isfinite(cx), "cx", "must be finite");
  SEWER3D_VALIDATE(std::isfinite(cy), "cy", "must be finite");
  for (double ki : k) SEWER3D_VALIDATE(std::isfinite(ki), "k", "must hold finite numbers");
  SEWER3D_VALIDATE(width <= kMaxImageSide && height <= kMaxImageSide, "width",
                   "an image of " << width << " x " << height << " px is larger than any camera ("
                                  << kMaxImageSide << " px a side at most)");
  constexpr std::int64_t kMaxPixels = std::int64_t{1} << 26;  // io's kMaxCameraPixels
  SEWER3D_VALIDATE(std::int64_t{width} * height <= kMaxPixels, "width",
                   width << "x" << height << " px is more than a camera has (" << (kMaxPixels >> 20)
                         << " M pixels at most)");
  // A field of view between 1° and 170°: outside it the focal length is a typo or a unit slip.
  const auto fov_deg = [](double side, double f) {
    return 2.0 * std::atan(side / (2.0 * f)) * 180 / M_PI;
  };
  for (const auto& [name, side, f] : {std::tuple{"fx", width, fx}, std::tuple{"fy", height, fy}}) {
    const double fov = fov_deg(side, f);
    SEWER3D_VALIDATE(
        fov >= 1.0 && fov <= 170.0, name,
        f << " px gives a field of view of " << fov << "° over " << side << " px; allowed 1..170°");
  }
  // Pixels are square to a few per cent on any sensor: fy ten times fx is a typo.
  SEWER3D_VALIDATE(fy >= 0.5 * fx && fy <= 2.0 * fx, "fy",
                   fy << " px is " << fy / fx << " times fx (" << fx
                      << " px); pixels that far from square are no camera's (0.5..2)");
  SEWER3D_VALIDATE(
      cx >= -0.5 && cx <= width - 0.5, "cx",
      "the principal point must lie in the image (-0.5.." << width - 0.5 << "), got " << cx);
  SEWER3D_VALIDATE(
      cy >= -0.5 && cy <= height - 0.5, "cy",
      "the principal point must lie in the image (-0.5.." << height - 0.5 << "), got " << cy);
  // The radial polynomial may fold back in the image's corners (those pixels are refused), but
  // not inside the circle the image's sides enclose: most of the image would be ambiguous.
  const double fold = FindFoldRadius(k);
  if (std::isfinite(fold)) {
    const double fold_distorted =
        fold * (1.0 + fold * fold * (k[0] + fold * fold * (k[1] + fold * fold * k[2])));
    const double inscribed = std::min(std::min(cx + 0.5, width - 0.5 - cx) / fx,
                                      std::min(cy + 0.5, height - 0.5 - cy) / fy);
    SEWER3D_VALIDATE(fold_distorted > inscribed, "k",
                     "the radial distortion folds back at normalised radius "
                         << fold_distorted << ", inside the image (its sides are at " << inscribed
                         << "): two rays would share most pixels");
  }
}

CameraModel::CameraModel(const CameraIntrinsics& intrinsics) : intrinsics_(intrinsics) {
  intrinsics_.Check();
  fold_radius_ = FindFoldRadius(intrinsics_.k);
  if (std::isfinite(fold_radius_)) {
    fold_radius_distorted_ = fold_radius_ * RadialFactor(fold_radius_ * fold_radius_);
  }
}

double CameraModel::RadialFactor(double r2) const {
  const auto& k = intrinsics_.k;
  return 1.0 + r2 * (k[0] + r2 * (k[1] + r2 * k[2]));
}

Eigen::Vector2d CameraModel::Distort(const Eigen::Vector2d& normalized) const {
  return normalized * RadialFactor(normalized.squaredNorm());
}

std::optional<Eigen::Vector2d> CameraModel::Undistort(const Eigen::Vector2d& distorted) const {
  const double rd = distorted.norm();
  if (rd == 0.0) return Eigen::Vector2d::Zero();
  if (!(rd < fold_radius_distorted_)) return std::nullopt;
  // The radial-only model reduces undistortion to the scalar equation f(r) = rd on the
  // increasing branch [0, fold): safeguarded Newton, bracket kept by bisection.
  double lo = 0.0;
  double hi = std::isfinite(fold_radius_) ? fold_radius_ : kMaxRadius;
  if (hi * RadialFactor(hi * hi) < rd) return std::nullopt;
  double r = std::clamp(rd, lo, hi);
  for (int it = 0; it < 100; ++it) {
    const double f = r * RadialFactor(r * r) - rd;
    if (f > 0.0)
      hi = r;
    else
      lo = r;
    if (std::abs(f) <= 1e-16 * rd) break;
    const double slope = RadialSlope(intrinsics_.k, r);
    double next = slope > 0.0 ? r - f / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == r) break;
    r = next;
  }
  return distorted * (r / rd);
}

Eigen::Vector2d CameraModel::PixelToDistorted(const Eigen::Vector2d& pixel) const {
  return {(pixel.x() - intrinsics_.cx) / intrinsics_.fx,
          (pixel.y() - intrinsics_.cy) / intrinsics_.fy};
}

Eigen::Vector2d CameraModel::DistortedToPixel(const Eigen::Vector2d& distorted) const {
  return {intrinsics_.fx * distorted.x() + intrinsics_.cx,
          intrinsics_.fy * distorted.y() + intrinsics_.cy};
}

std::optional<Eigen::Vector2d> CameraModel::Project(const Eigen::Vector3d& p_in_camera) const {
  if (!(p_in_camera.z() > 0.0)) return std::nullopt;
  const Eigen::Vector2d normalized = p_in_camera.head<2>() / p_in_camera.z();
  if (!(normalized.norm() < fold_radius_)) return std::nullopt;
  return DistortedToPixel(Distort(normalized));
}

std::optional<Eigen::Vector2d> CameraModel::Unproject(const Eigen::Vector2d& pixel) const {
  return Undistort(PixelToDistorted(pixel));
}

std::optional<Eigen::Vector3d> CameraModel::Ray(const Eigen::Vector2d& pixel) const {
  const auto normalized = Unproject(pixel);
  if (!normalized) return std::nullopt;
  return Eigen::Vector3d(normalized->x(), normalized->y(), 1.0).normalized();
}

bool CameraModel::WholeImageInvertible() const {
  const double w = intrinsics_.width, h = intrinsics_.height;
  for (const Eigen::Vector2d& corner :
       {Eigen::Vector2d(-0.5, -0.5), Eigen::Vector2d(w - 0.5, -0.5), Eigen::Vector2d(-0.5, h - 0.5),
        Eigen::Vector2d(w - 0.5, h - 0.5)}) {
    if (!(PixelToDistorted(corner).norm() < fold_radius_distorted_)) return false;
  }
  return true;
}

}  // namespace sewer3d
