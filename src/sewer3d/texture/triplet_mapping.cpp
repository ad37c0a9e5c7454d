#include "sewer3d/texture/triplet_mapping.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <tuple>
#include <vector>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Bilinear depth at a pixel; NaN outside the image or where a neighbour has none.
double DepthAt(const cv::Mat1f& depth, const Eigen::Vector2d& p) {
  const int u0 = static_cast<int>(std::floor(p.x())), v0 = static_cast<int>(std::floor(p.y()));
  if (u0 < 0 || v0 < 0 || u0 + 1 >= depth.cols || v0 + 1 >= depth.rows) return NAN;
  const double a = p.x() - u0, b = p.y() - v0;
  return (1 - b) * ((1 - a) * depth(v0, u0) + a * depth(v0, u0 + 1)) +
         b * ((1 - a) * depth(v0 + 1, u0) + a * depth(v0 + 1, u0 + 1));
}

// 8-bit grey of both images on one scale (AKAZE wants a known range; the images may be linear
// floats of any scale).
void CommonGrey(const cv::Mat3f& a, const cv::Mat3f& b, cv::Mat1b& grey_a, cv::Mat1b& grey_b) {
  cv::Mat1f fa, fb;
  cv::cvtColor(a, fa, cv::COLOR_BGR2GRAY);
  cv::cvtColor(b, fb, cv::COLOR_BGR2GRAY);
  double max_a = 0.0, max_b = 0.0;
  cv::minMaxLoc(fa, nullptr, &max_a);
  cv::minMaxLoc(fb, nullptr, &max_b);
  const double scale = 255.0 / std::max({max_a, max_b, 1e-12});
  fa.convertTo(grey_a, CV_8U, scale);
  fb.convertTo(grey_b, CV_8U, scale);
}

// Matches before → after surviving the ratio test and the cross check.
std::vector<cv::DMatch> MatchFeatures(const cv::Mat& desc_b, const cv::Mat& desc_a, double ratio) {
  std::vector<cv::DMatch> out;
  if (desc_b.rows < 2 || desc_a.rows < 2) return out;
  cv::BFMatcher matcher(cv::NORM_HAMMING);
  std::vector<std::vector<cv::DMatch>> forward, backward;
  matcher.knnMatch(desc_b, desc_a, forward, 2);
  matcher.knnMatch(desc_a, desc_b, backward, 2);
  for (const auto& m : forward) {
    if (m.size() < 2 || m[0].distance >= ratio * m[1].distance) continue;
    const auto& back = backward[m[0].trainIdx];
    if (!back.empty() && back[0].trainIdx == m[0].queryIdx) out.push_back(m[0]);
  }
  return out;
}

// The before-feature's 3-D point (before frame) on the pattern's depth surface: along the ray
// of its pixel, z such that the point, seen from the pattern camera, has the map's depth
// (fixed-point steps from the depth at the same pixel). The camera moved only ~0.5 mm, so the
// first guess is already close; the steps remove the few-pixel shift on sloped walls.
std::optional<Eigen::Vector3d> Lift(const CameraModel& camera, const cv::Mat1f& depth,
                                    const Eigen::Vector2d& pixel,
                                    const Rigid3d& pattern_from_before) {
  const auto xy = camera.Unproject(pixel);
  if (!xy) return std::nullopt;
  const Eigen::Vector3d ray(xy->x(), xy->y(), 1.0);
  double s = DepthAt(depth, pixel);
  const double dz_ds = (pattern_from_before.rotation * ray).z();
  for (int i = 0; i < 3 && std::isfinite(s); ++i) {
    const Eigen::Vector3d p = pattern_from_before * (ray * s);
    const auto q = camera.Project(p);
    if (!q) return std::nullopt;
    s += (DepthAt(depth, *q) - p.z()) / dz_ds;
  }
  if (!(s > 0.0)) return std::nullopt;
  return ray * s;
}

Rigid3d PatternFromBefore(const Rigid3d& after_from_before, const TripletTimes& t) {
  const double s = (t.pattern_s - t.before_s) / (t.after_s - t.before_s);
  return InterpolatePose(Rigid3d::Identity(), after_from_before.Inverse(), s).Inverse();
}

// Camera motion from AKAZE matches and PnP; nullopt when too few inliers or implausible.
std::optional<Rigid3d> MotionFromFeatures(const cv::Mat3f& before, const cv::Mat3f& after,
                                          const cv::Mat1f& depth, const CameraModel& camera,
                                          const TripletTimes& times, const TripletMappingOptions& o,
                                          TripletMappingReport& report) {
  cv::Mat1b grey_b, grey_a;
  CommonGrey(before, after, grey_b, grey_a);
  const auto akaze =
      cv::AKAZE::create(cv::AKAZE::DESCRIPTOR_MLDB, 0, 3, static_cast<float>(o.akaze_threshold));
  std::vector<cv::KeyPoint> kp_b, kp_a;
  cv::Mat desc_b, desc_a;
  // Wide images are searched at a reduced size (the motion needs hundreds of features, not
  // tens of thousands); the keypoints are scaled back to full-size pixels.
  const double shrink = grey_b.cols > o.max_detect_width_px
                            ? static_cast<double>(o.max_detect_width_px) / grey_b.cols
                            : 1.0;
  for (auto [grey, kp, desc] : {std::tie(grey_b, kp_b, desc_b), std::tie(grey_a, kp_a, desc_a)}) {
    cv::Mat1b small = grey;
    if (shrink < 1.0) cv::resize(grey, small, cv::Size(), shrink, shrink, cv::INTER_AREA);
    akaze->detectAndCompute(small, cv::noArray(), kp, desc);
    if (shrink < 1.0) {
      // Pixel centres at integers: x_full = (x_small + 0.5) / shrink − 0.5.
      for (cv::KeyPoint& k : kp) {
        k.pt.x = static_cast<float>((k.pt.x + 0.5) / shrink - 0.5);
        k.pt.y = static_cast<float>((k.pt.y + 0.5) / shrink - 0.5);
      }
    }
  }
  report.features_before = static_cast<int>(kp_b.size());
  report.features_after = static_cast<int>(kp_a.size());
  const std::vector<cv::DMatch> matches = MatchFeatures(desc_b, desc_a, o.ratio);
  report.matches = static_cast<int>(matches.size());
  // Pass 0 lifts by the depth at the before pixel; pass 1 re-lifts the inliers through the
  // interpolated pattern pose and refines (LM) on them.
  Rigid3d after_from_before;
  std::vector<int> inliers;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<cv::Point3d> object;
    std::vector<cv::Point2d> image;
    std::vector<int> ids;
    const Rigid3d pattern_from_before =
        pass == 0 ? Rigid3d::Identity() : PatternFromBefore(after_from_before, times);
    const std::vector<int> candidates = [&] {
      if (pass == 1) return inliers;
      std::vector<int> all(matches.size());
      for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
      return all;
    }();
    for (const int i : candidates) {
      const cv::Point2f pb = kp_b[matches[i].queryIdx].pt, pa = kp_a[matches[i].trainIdx].pt;
      const auto x = Lift(camera, depth, {pb.x, pb.y}, pattern_from_before);
      const auto xa = camera.Unproject({pa.x, pa.y});
      if (!x || !xa) continue;
      object.emplace_back(x->x(), x->y(), x->z());
      image.emplace_back(xa->x(), xa->y());
      ids.push_back(i);
    }
    if (static_cast<int>(object.size()) < std::max(o.min_inliers, 6)) return std::nullopt;
    cv::Mat rvec = cv::Mat::zeros(3, 1, CV_64F), tvec = cv::Mat::zeros(3, 1, CV_64F);
    const cv::Matx33d unit = cv::Matx33d::eye();
    if (pass == 0) {
      std::vector<int> in;
      const double threshold = o.ransac_px / camera.intrinsics().fx;
      if (!cv::solvePnPRansac(object, image, unit, cv::noArray(), rvec, tvec, true, 200,
                              static_cast<float>(threshold), 0.999, in, cv::SOLVEPNP_ITERATIVE) ||
          static_cast<int>(in.size()) < o.min_inliers) {
        report.inliers = static_cast<int>(in.size());
        return std::nullopt;
      }
      inliers.clear();
      for (const int k : in) inliers.push_back(ids[k]);
    } else {
      const Eigen::AngleAxisd angle_axis(after_from_before.rotation);
      const Eigen::Vector3d rotation_vector = angle_axis.angle() * angle_axis.axis();
      cv::eigen2cv(rotation_vector, rvec);
      cv::eigen2cv(after_from_before.translation, tvec);
      inliers = ids;
    }
    cv::solvePnPRefineLM(object, image, unit, cv::noArray(), rvec, tvec);
    cv::Matx33d r;
    cv::Rodrigues(rvec, r);
    Eigen::Matrix3d re;
    cv::cv2eigen(cv::Mat(r), re);
    after_from_before =
        Rigid3d(re, Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2)));
    report.inliers = static_cast<int>(inliers.size());
    double sum2 = 0.0;
    for (size_t k = 0; k < object.size(); ++k) {
      if (pass == 0 && std::find(inliers.begin(), inliers.end(), ids[k]) == inliers.end()) continue;
      const auto q = camera.Project(after_from_before *
                                    Eigen::Vector3d(object[k].x, object[k].y, object[k].z));
      const auto pa = kp_a[matches[ids[k]].trainIdx].pt;
      sum2 += q ? (*q - Eigen::Vector2d(pa.x, pa.y)).squaredNorm() : 1e6;
    }
    report.reprojection_rms_px = std::sqrt(sum2 / std::max<size_t>(1, inliers.size()));
  }
  if (after_from_before.translation.norm() > o.max_motion_mm) return std::nullopt;
  return after_from_before;
}

}  // namespace

void TripletTimes::Check() const {
  SEWER3D_VALIDATE(after_s > before_s, "after_s", "must be later than before_s");
  SEWER3D_VALIDATE(pattern_s >= before_s && pattern_s <= after_s, "pattern_s",
                   "must lie between before_s and after_s, got " << pattern_s);
}

void TripletMappingOptions::Check() const {
  ValidatePositive("akaze_threshold", akaze_threshold);
  SEWER3D_VALIDATE(ratio > 0.0 && ratio <= 1.0, "ratio", "must be in (0, 1], got " << ratio);
  ValidatePositive("ransac_px", ransac_px);
  SEWER3D_VALIDATE(min_inliers >= 6, "min_inliers", "must be >= 6, got " << min_inliers);
  ValidatePositive("max_motion_mm", max_motion_mm);
  SEWER3D_VALIDATE(max_detect_width_px >= 64, "max_detect_width_px",
                   "must be >= 64, got " << max_detect_width_px);
}

Rigid3d InterpolatePose(const Rigid3d& start, const Rigid3d& end, double s) {
  return {start.rotation.slerp(s, end.rotation),
          (1.0 - s) * start.translation + s * end.translation};
}

TripletMappingResult MapTripletToPattern(const cv::Mat3f& before, const cv::Mat3f& after,
                                         const cv::Mat1f& depth_mm, const CameraModel& camera,
                                         const TripletTimes& times,
                                         const std::optional<Eigen::Vector3d>& velocity_mm_s,
                                         const TripletMappingOptions& options) {
  options.Check();
  times.Check();
  SEWER3D_VALIDATE(before.size() == after.size() && before.size() == depth_mm.size(), "depth_mm",
                   "texture images and depth map must have one size");
  const auto t0 = std::chrono::steady_clock::now();
  TripletMappingResult result;
  TripletMappingReport& report = result.report;
  const double w_before = (times.after_s - times.pattern_s) / (times.after_s - times.before_s);
  // Fallback colour: the image nearer in time, as it is.
  result.color = (w_before >= 0.5 ? before : after).clone();
  if (auto motion = MotionFromFeatures(before, after, depth_mm, camera, times, options, report)) {
    report.method = "akaze";
    result.after_from_before = *motion;
  } else if (velocity_mm_s) {
    report.method = "odometry";
    report.reprojection_rms_px = 0.0;
    // The camera moves by v Δt; a point fixed in the world moves by −v Δt in the camera frame.
    result.after_from_before = {Eigen::Quaterniond::Identity(),
                                -(*velocity_mm_s) * (times.after_s - times.before_s)};
  } else {
    report.method = "none";
  }
  report.motion_mm = result.after_from_before.translation.norm();
  report.rotation_deg =
      Eigen::AngleAxisd(result.after_from_before.rotation).angle() * 180.0 / std::numbers::pi;
  if (report.method != "none") {
    result.pattern_from_before = PatternFromBefore(result.after_from_before, times);
    const Rigid3d before_from_pattern = result.pattern_from_before.Inverse();
    const Rigid3d after_from_pattern = result.after_from_before * before_from_pattern;
    cv::Mat2f map_b(depth_mm.size(), cv::Vec2f(-1e6F, -1e6F)), map_a = map_b.clone();
    cv::parallel_for_(cv::Range(0, depth_mm.rows), [&](const cv::Range& rows) {
      for (int v = rows.start; v < rows.end; ++v) {
        for (int u = 0; u < depth_mm.cols; ++u) {
          const float z = depth_mm(v, u);
          const auto xy = z > 0.0F ? camera.Unproject({double(u), double(v)}) : std::nullopt;
          if (!xy) continue;
          const Eigen::Vector3d p = Eigen::Vector3d(xy->x(), xy->y(), 1.0) * z;
          if (const auto q = camera.Project(before_from_pattern * p))
            map_b(v, u) = {float(q->x()), float(q->y())};
          if (const auto q = camera.Project(after_from_pattern * p))
            map_a(v, u) = {float(q->x()), float(q->y())};
        }
      }
    });
    cv::Mat3f from_b, from_a;
    const cv::Scalar none(kNaN, kNaN, kNaN);
    cv::remap(before, from_b, map_b, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, none);
    cv::remap(after, from_a, map_a, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, none);
    for (int v = 0; v < depth_mm.rows; ++v) {
      for (int u = 0; u < depth_mm.cols; ++u) {
        const cv::Vec3f b = from_b(v, u), a = from_a(v, u);
        const bool has_b = std::isfinite(b[0] + b[1] + b[2]);
        const bool has_a = std::isfinite(a[0] + a[1] + a[2]);
        if (!has_b && !has_a) continue;
        const auto wb = static_cast<float>(!has_a ? 1.0 : !has_b ? 0.0 : w_before);
        result.color(v, u) =
            wb * (has_b ? b : cv::Vec3f()) + (1.0F - wb) * (has_a ? a : cv::Vec3f());
        ++report.mapped_pixels;
      }
    }
  }
  report.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace sewer3d
