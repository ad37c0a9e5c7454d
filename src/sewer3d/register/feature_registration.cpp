#include "sewer3d/register/feature_registration.hpp"

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "sewer3d/core/check.hpp"
#include "sewer3d/register/depth_geometry.hpp"

namespace sewer3d {
namespace {

struct Features {
  std::vector<cv::KeyPoint> keypoints;  ///< in the full image's pixels
  cv::Mat descriptors;
  double scale = 1.0;  ///< detection image / full image
};

void CheckImage(const RgbdImage& image, const CameraModel& camera, const char* name) {
  const CameraIntrinsics& in = camera.intrinsics();
  SEWER3D_VALIDATE(image.color_bgr.cols == in.width && image.color_bgr.rows == in.height &&
                       image.depth.size() == image.color_bgr.size(),
                   name,
                   "colour " << image.color_bgr.cols << " x " << image.color_bgr.rows
                             << " and depth " << image.depth.cols << " x " << image.depth.rows
                             << " must both be the camera's " << in.width << " x " << in.height);
}

// SIFT where the depth map has values (elsewhere a keypoint could not be lifted anyway).
Features Detect(const RgbdImage& image, const FeatureRegistrationOptions& options) {
  cv::Mat1b gray;
  cv::cvtColor(image.color_bgr, gray, cv::COLOR_BGR2GRAY);
  // NOLINTNEXTLINE(misc-redundant-expression): NaN compares unequal to itself
  cv::Mat1b mask = (image.depth == image.depth);  // false where NaN
  Features f;
  if (options.max_detect_width_px > 0 && gray.cols > options.max_detect_width_px) {
    f.scale = static_cast<double>(options.max_detect_width_px) / gray.cols;
    const cv::Size size(options.max_detect_width_px,
                        std::max(1, static_cast<int>(std::lround(gray.rows * f.scale))));
    cv::resize(gray, gray, size, 0, 0, cv::INTER_AREA);
    cv::resize(mask, mask, size, 0, 0, cv::INTER_NEAREST);
  }
  const cv::Ptr<cv::SIFT> sift =
      cv::SIFT::create(options.max_keypoints, 3, options.contrast_threshold, 10.0, 1.6);
  sift->detectAndCompute(gray, mask, f.keypoints, f.descriptors);
  for (cv::KeyPoint& k : f.keypoints) {  // pixel centres at integers in both images
    k.pt.x = static_cast<float>((k.pt.x + 0.5) / f.scale - 0.5);
    k.pt.y = static_cast<float>((k.pt.y + 0.5) / f.scale - 0.5);
    k.size = static_cast<float>(k.size / f.scale);
  }
  return f;
}

// Ratio test a → b, and (optionally) b's best match in a must be the same keypoint.
std::vector<cv::DMatch> Match(const Features& a, const Features& b,
                              const FeatureRegistrationOptions& options) {
  std::vector<cv::DMatch> out;
  if (a.keypoints.size() < 2 || b.keypoints.size() < 2) return out;
  const cv::BFMatcher matcher(cv::NORM_L2);
  std::vector<std::vector<cv::DMatch>> ab, ba;
  matcher.knnMatch(a.descriptors, b.descriptors, ab, 2);
  if (options.cross_check) matcher.knnMatch(b.descriptors, a.descriptors, ba, 1);
  for (const auto& m : ab) {
    if (m.size() < 2 || !(m[0].distance < options.ratio * m[1].distance)) continue;
    if (options.cross_check &&
        (ba[m[0].trainIdx].empty() || ba[m[0].trainIdx][0].trainIdx != m[0].queryIdx))
      continue;
    out.push_back(m[0]);
  }
  return out;
}

// The 3-D point of a keypoint: bilinear depth along the keypoint's own ray.
std::optional<Eigen::Vector3d> Lift(const cv::KeyPoint& k, const RgbdImage& image,
                                    const CameraModel& camera, double max_spread) {
  const Eigen::Vector2d px(k.pt.x, k.pt.y);
  const auto z = SampleBilinear(image.depth, px, max_spread);
  if (!z || !(*z > 0.0)) return std::nullopt;
  const auto xy = camera.Unproject(px);
  if (!xy) return std::nullopt;
  return Eigen::Vector3d(xy->x() * *z, xy->y() * *z, *z);
}

}  // namespace

void FeatureRegistrationOptions::Check() const {
  ValidateNotNegative("max_keypoints", max_keypoints);
  ValidatePositive("contrast_threshold", contrast_threshold);
  SEWER3D_VALIDATE(ratio > 0.0 && ratio <= 1.0, "ratio", "must lie in (0, 1], got " << ratio);
  ValidatePositive("max_depth_spread_mm", max_depth_spread_mm);
  ValidateNotNegative("max_detect_width_px", max_detect_width_px);
  CheckWithin("noise.", [&] { noise.Check(); });
  CheckWithin("points.", [&] { points.Check(); });
}

FeatureRegistrationResult RegisterFeatures(const RgbdImage& a, const CameraModel& camera_a,
                                           const RgbdImage& b, const CameraModel& camera_b,
                                           const FeatureRegistrationOptions& options) {
  options.Check();
  CheckImage(a, camera_a, "a");
  CheckImage(b, camera_b, "b");
  FeatureRegistrationResult out;
  FeatureRegistrationReport& report = out.report;
  const Features fa = Detect(a, options), fb = Detect(b, options);
  report.keypoints_a = static_cast<int>(fa.keypoints.size());
  report.keypoints_b = static_cast<int>(fb.keypoints.size());
  const std::vector<cv::DMatch> matches = Match(fa, fb, options);
  report.matches = static_cast<int>(matches.size());

  // A keypoint found at scale s is localised s times less finely in the full image: the noise
  // model sees the detection image's focal length.
  const double focal_a = fa.scale * std::sqrt(camera_a.intrinsics().fx * camera_a.intrinsics().fy);
  const double focal_b = fb.scale * std::sqrt(camera_b.intrinsics().fx * camera_b.intrinsics().fy);
  std::vector<PointMatch> points;
  for (const cv::DMatch& m : matches) {
    const auto pa = Lift(fa.keypoints[m.queryIdx], a, camera_a, options.max_depth_spread_mm);
    const auto pb = Lift(fb.keypoints[m.trainIdx], b, camera_b, options.max_depth_spread_mm);
    if (!pa || !pb) continue;
    points.push_back({*pa, *pb, options.noise.PointCovariance(*pa, focal_a),
                      options.noise.PointCovariance(*pb, focal_b)});
  }
  report.with_depth = static_cast<int>(points.size());

  const PointRegistrationResult r = RegisterPoints(points, options.points);
  report.ransac_inliers = r.ransac_inliers;
  report.ransac_iterations = r.ransac_iterations;
  report.inliers = static_cast<int>(r.inliers.size());
  report.variance_factor = r.variance_factor;
  out.converged = r.converged;
  out.a_from_b = r.a_from_b;
  out.information = r.information;
  out.inliers = report.inliers;
  out.rms_mm = r.rms_mm;
  return out;
}

}  // namespace sewer3d
