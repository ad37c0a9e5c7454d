#include "sewer3d/texture/depth_prior.hpp"

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "sewer3d/core/check.hpp"
#include "sewer3d/texture/shading.hpp"

namespace sewer3d {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Push–pull fill of `value` where `weight` is 0: returns `value` with every pixel filled from
// the weighted averages of coarser levels (bilinear), measured pixels unchanged.
cv::Mat1f PushPull(const cv::Mat1f& value, const cv::Mat1f& weight) {
  if (value.rows <= 2 || value.cols <= 2) {
    const double w = cv::sum(weight)[0];
    const double mean = w > 0 ? cv::sum(value.mul(weight))[0] / w : 0.0;
    cv::Mat1f out = value.clone();
    out.setTo(mean, weight <= 0);
    return out;
  }
  // Pull: weighted 2 x 2 averages (sums of value · weight and of weight).
  cv::Mat1f weighted_sum, weight_sum;
  cv::Size half((value.cols + 1) / 2, (value.rows + 1) / 2);
  cv::resize(value.mul(weight), weighted_sum, half, 0, 0, cv::INTER_AREA);
  cv::resize(weight, weight_sum, half, 0, 0, cv::INTER_AREA);
  cv::Mat1f coarse(half, 0.0f), coarse_weight(half, 0.0f);
  for (int v = 0; v < half.height; ++v) {
    for (int u = 0; u < half.width; ++u) {
      if (weight_sum(v, u) > 0) {
        coarse(v, u) = weighted_sum(v, u) / weight_sum(v, u);
        coarse_weight(v, u) = std::min(1.0f, 4.0f * weight_sum(v, u));
      }
    }
  }
  // Push: the filled coarse level, bilinear, into this level's holes (partly weighted pixels
  // blend toward it).
  cv::Mat1f up;
  cv::resize(PushPull(coarse, coarse_weight), up, value.size(), 0, 0, cv::INTER_LINEAR);
  cv::Mat1f out(value.size());
  for (int v = 0; v < value.rows; ++v) {
    for (int u = 0; u < value.cols; ++u) {
      const float w = std::min(1.0f, weight(v, u));
      out(v, u) = w * value(v, u) + (1.0f - w) * up(v, u);
    }
  }
  return out;
}

}  // namespace

cv::Mat1f PipePriorDepth(const cv::Mat2f& normalised, const Rigid3d& carrier_from_camera,
                         double diameter_mm) {
  ValidatePositive("diameter_mm", diameter_mm);
  const double radius2 = 0.25 * diameter_mm * diameter_mm;
  const Eigen::Matrix3d rotation = carrier_from_camera.RotationMatrix();
  const Eigen::Vector3d& o = carrier_from_camera.translation;
  cv::Mat1f depth(normalised.size(), kNaN);
  // The ray o + s d (d = rotation · (x, y, 1), so s is the camera z) meets x² + y² = r² in the
  // carrier frame at the larger root; a camera outside the pipe (c ≥ 0) sees no prior.
  const double c = o.x() * o.x() + o.y() * o.y() - radius2;
  if (c >= 0.0) return depth;
  cv::parallel_for_(cv::Range(0, depth.rows), [&](const cv::Range& rows) {
    for (int v = rows.start; v < rows.end; ++v) {
      for (int u = 0; u < depth.cols; ++u) {
        const cv::Vec2f& xy = normalised(v, u);
        if (!std::isfinite(xy[0])) continue;
        const Eigen::Vector3d d = rotation * Eigen::Vector3d(xy[0], xy[1], 1.0);
        const double a = d.x() * d.x() + d.y() * d.y();
        if (a < 1e-12) continue;
        const double b = 2.0 * (o.x() * d.x() + o.y() * d.y());
        const double s = (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
        if (s > 0.0) depth(v, u) = static_cast<float>(s);
      }
    }
  });
  return depth;
}

cv::Mat1f PipePriorDepth(const CameraModel& camera, const Rigid3d& carrier_from_camera,
                         double diameter_mm) {
  return PipePriorDepth(NormalisedCoordinates(camera), carrier_from_camera, diameter_mm);
}

cv::Mat1f FillDepthFromPrior(const cv::Mat1f& depth_mm, const cv::Mat1f& prior_mm) {
  SEWER3D_VALIDATE(depth_mm.size() == prior_mm.size(), "prior_mm", "must have the depth's size");
  cv::Mat1f ratio(depth_mm.size(), 0.0f), weight(depth_mm.size(), 0.0f);
  bool any = false;
  for (int v = 0; v < depth_mm.rows; ++v) {
    for (int u = 0; u < depth_mm.cols; ++u) {
      const float z = depth_mm(v, u), p = prior_mm(v, u);
      if (std::isfinite(z) && std::isfinite(p) && p > 0) {
        ratio(v, u) = z / p;
        weight(v, u) = 1.0f;
        any = true;
      }
    }
  }
  const cv::Mat1f filled_ratio = any ? PushPull(ratio, weight) : cv::Mat1f(ratio.size(), 1.0f);
  cv::Mat1f out = depth_mm.clone();
  for (int v = 0; v < out.rows; ++v) {
    for (int u = 0; u < out.cols; ++u) {
      if (std::isnan(out(v, u))) out(v, u) = prior_mm(v, u) * filled_ratio(v, u);
    }
  }
  return out;
}

}  // namespace sewer3d
