#include "sewer3d/register/depth_geometry.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();

bool Finite(const cv::Vec3f& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}
Eigen::Vector3d ToEigen(const cv::Vec3f& v) { return {v[0], v[1], v[2]}; }

// The four pixels around `pixel` and their bilinear weights; false outside the image.
bool Corners(int rows, int cols, const Eigen::Vector2d& pixel, int* u0, int* v0, double* fu,
             double* fv) {
  if (cols < 2 || rows < 2) return false;
  if (!(pixel.x() >= 0.0 && pixel.y() >= 0.0 && pixel.x() <= cols - 1 && pixel.y() <= rows - 1))
    return false;
  *u0 = std::min(static_cast<int>(pixel.x()), cols - 2);
  *v0 = std::min(static_cast<int>(pixel.y()), rows - 2);
  *fu = pixel.x() - *u0;
  *fv = pixel.y() - *v0;
  return true;
}

// The mean of each smooth_px × smooth_px box that holds no NaN; NaN elsewhere. (OpenCV's box
// filter keeps running sums, so one NaN would poison the rest of its row and column.)
cv::Mat3f BoxMeanOfFullBoxes(const cv::Mat3f& points, int smooth_px) {
  cv::Mat3f zeroed(points.size(), cv::Vec3f(0, 0, 0));
  cv::Mat1f valid(points.size(), 0.0f);
  for (int v = 0; v < points.rows; ++v) {
    for (int u = 0; u < points.cols; ++u) {
      if (!Finite(points(v, u))) continue;
      zeroed(v, u) = points(v, u);
      valid(v, u) = 1.0f;
    }
  }
  const cv::Size box(smooth_px, smooth_px);
  cv::Mat3f sums;
  cv::Mat1f counts;
  cv::boxFilter(zeroed, sums, -1, box, cv::Point(-1, -1), false, cv::BORDER_CONSTANT);
  cv::boxFilter(valid, counts, -1, box, cv::Point(-1, -1), false, cv::BORDER_CONSTANT);
  const float full = static_cast<float>(smooth_px * smooth_px) - 0.5f;
  cv::Mat3f out(points.size(), cv::Vec3f(kNaN, kNaN, kNaN));
  for (int v = 0; v < points.rows; ++v)
    for (int u = 0; u < points.cols; ++u)
      if (counts(v, u) > full) out(v, u) = sums(v, u) / counts(v, u);
  return out;
}

}  // namespace

cv::Mat3f PointMap(const cv::Mat1f& depth, const CameraModel& camera) {
  const CameraIntrinsics& in = camera.intrinsics();
  SEWER3D_VALIDATE(depth.cols == in.width && depth.rows == in.height, "depth",
                   "is " << depth.cols << " x " << depth.rows << ", the camera " << in.width
                         << " x " << in.height);
  cv::Mat3f out(depth.size(), cv::Vec3f(kNaN, kNaN, kNaN));
  for (int v = 0; v < depth.rows; ++v) {
    for (int u = 0; u < depth.cols; ++u) {
      const float z = depth(v, u);
      if (!(std::isfinite(z) && z > 0.0f)) continue;
      const auto xy = camera.Unproject(Eigen::Vector2d(u, v));
      if (!xy) continue;
      out(v, u) = cv::Vec3f(static_cast<float>(xy->x() * z), static_cast<float>(xy->y() * z), z);
    }
  }
  return out;
}

cv::Mat3f NormalMap(const cv::Mat3f& points_in, int step_px, int smooth_px, double max_step_mm) {
  SEWER3D_CHECK(step_px >= 1 && smooth_px >= 1);
  const cv::Mat3f points = smooth_px > 1 ? BoxMeanOfFullBoxes(points_in, smooth_px) : points_in;
  cv::Mat3f out(points.size(), cv::Vec3f(kNaN, kNaN, kNaN));
  for (int v = step_px; v + step_px < points.rows; ++v) {
    for (int u = step_px; u + step_px < points.cols; ++u) {
      const cv::Vec3f& c = points(v, u);
      const cv::Vec3f& l = points(v, u - step_px);
      const cv::Vec3f& r = points(v, u + step_px);
      const cv::Vec3f& t = points(v - step_px, u);
      const cv::Vec3f& b = points(v + step_px, u);
      if (!Finite(c) || !Finite(l) || !Finite(r) || !Finite(t) || !Finite(b)) continue;
      const Eigen::Vector3d pc = ToEigen(c);
      if ((ToEigen(l) - pc).norm() > max_step_mm || (ToEigen(r) - pc).norm() > max_step_mm ||
          (ToEigen(t) - pc).norm() > max_step_mm || (ToEigen(b) - pc).norm() > max_step_mm)
        continue;
      Eigen::Vector3d n = (ToEigen(r) - ToEigen(l)).cross(ToEigen(b) - ToEigen(t));
      if (!(n.norm() > 0.0)) continue;
      n.normalize();
      if (n.dot(pc) > 0.0) n = -n;  // toward the camera
      out(v, u) = cv::Vec3f(static_cast<float>(n.x()), static_cast<float>(n.y()),
                            static_cast<float>(n.z()));
    }
  }
  return out;
}

double NormalNoiseVariance(const cv::Mat3f& normals, int offset_px) {
  SEWER3D_CHECK(offset_px >= 1);
  const int k = offset_px;
  std::vector<double> d2;
  for (int v = k; v + k < normals.rows; v += k) {
    for (int u = k; u + k < normals.cols; u += k) {
      const cv::Vec3f* n[5] = {&normals(v, u), &normals(v, u - k), &normals(v, u + k),
                               &normals(v - k, u), &normals(v + k, u)};
      if (!std::all_of(std::begin(n), std::end(n), [](const cv::Vec3f* x) { return Finite(*x); }))
        continue;
      const Eigen::Vector3d mean =
          0.25 * (ToEigen(*n[1]) + ToEigen(*n[2]) + ToEigen(*n[3]) + ToEigen(*n[4]));
      d2.push_back((ToEigen(*n[0]) - mean).squaredNorm());
    }
  }
  if (d2.size() < 10) return 0.0;
  std::nth_element(d2.begin(), d2.begin() + static_cast<std::ptrdiff_t>(d2.size() / 2), d2.end());
  // d = e₀ − mean(e₁..e₄) has per-component variance σ² (1 + 1/4); |d|² over the two tangential
  // components is exponential with mean 2 · 1.25 σ² and median 2 · 1.25 σ² · ln 2.
  return d2[d2.size() / 2] / (2.0 * 1.25 * std::log(2.0));
}

std::optional<double> SampleBilinear(const cv::Mat1f& map, const Eigen::Vector2d& pixel,
                                     double max_spread) {
  int u0 = 0, v0 = 0;
  double fu = 0.0, fv = 0.0;
  if (!Corners(map.rows, map.cols, pixel, &u0, &v0, &fu, &fv)) return std::nullopt;
  const double a = map(v0, u0), b = map(v0, u0 + 1), c = map(v0 + 1, u0), d = map(v0 + 1, u0 + 1);
  if (!(std::isfinite(a) && std::isfinite(b) && std::isfinite(c) && std::isfinite(d)))
    return std::nullopt;
  const double lo = std::min(std::min(a, b), std::min(c, d));
  const double hi = std::max(std::max(a, b), std::max(c, d));
  if (hi - lo > max_spread) return std::nullopt;
  return (1 - fv) * ((1 - fu) * a + fu * b) + fv * ((1 - fu) * c + fu * d);
}

std::optional<Eigen::Vector3d> SampleBilinear(const cv::Mat3f& map, const Eigen::Vector2d& pixel,
                                              double max_spread) {
  int u0 = 0, v0 = 0;
  double fu = 0.0, fv = 0.0;
  if (!Corners(map.rows, map.cols, pixel, &u0, &v0, &fu, &fv)) return std::nullopt;
  const cv::Vec3f* corner[4] = {&map(v0, u0), &map(v0, u0 + 1), &map(v0 + 1, u0),
                                &map(v0 + 1, u0 + 1)};
  for (const cv::Vec3f* c : corner)
    if (!Finite(*c)) return std::nullopt;
  const Eigen::Vector3d a = ToEigen(*corner[0]), b = ToEigen(*corner[1]), c = ToEigen(*corner[2]),
                        d = ToEigen(*corner[3]);
  const Eigen::Vector3d mean = 0.25 * (a + b + c + d);
  const double spread = std::max(std::max((a - mean).norm(), (b - mean).norm()),
                                 std::max((c - mean).norm(), (d - mean).norm()));
  if (spread > max_spread) return std::nullopt;
  return (1 - fv) * ((1 - fu) * a + fu * b) + fv * ((1 - fu) * c + fu * d);
}

std::vector<Eigen::Vector3d> SampleDepthPoints(const cv::Mat1f& depth, const CameraModel& camera,
                                               int step_px) {
  SEWER3D_CHECK(step_px >= 1);
  std::vector<Eigen::Vector3d> out;
  for (int v = step_px / 2; v < depth.rows; v += step_px) {
    for (int u = step_px / 2; u < depth.cols; u += step_px) {
      const float z = depth(v, u);
      if (!(std::isfinite(z) && z > 0.0f)) continue;
      if (const auto xy = camera.Unproject(Eigen::Vector2d(u, v)))
        out.emplace_back(xy->x() * z, xy->y() * z, z);
    }
  }
  return out;
}

}  // namespace sewer3d
