#include "sewer3d/calib/camera_calibration.hpp"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <tuple>

#include "sewer3d/calib/reprojection.hpp"
#include "sewer3d/core/check.hpp"

namespace sewer3d {

std::vector<Eigen::Vector3d> BoardCorners(int cols, int rows, double square_mm) {
  SEWER3D_VALIDATE(cols >= 2 && rows >= 2, "board",
                   "needs at least 2x2 inner corners, got " << cols << "x" << rows);
  ValidatePositive("square_mm", square_mm);
  std::vector<Eigen::Vector3d> corners;
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) corners.emplace_back(j * square_mm, i * square_mm, 0.0);
  }
  return corners;
}

constexpr double kMaxRelativeFocalSigma = 0.05;

CalibrationResult CalibrateCamera(const std::vector<CalibrationView>& views,
                                  const std::vector<Eigen::Vector3d>& board, int width, int height,
                                  const CalibrationOptions& options) {
  SEWER3D_VALIDATE(views.size() >= 3, "",
                   "calibration needs at least 3 views, got " << views.size());
  SEWER3D_CHECK(width > 0 && height > 0, "image size");
  for (const CalibrationView& v : views)
    SEWER3D_CHECK(v.corners_px.size() == board.size(), "view without all corners");
  // Zhang's initialisation (OpenCV): focal lengths from the views' homographies with the
  // principal point at the image centre, then each view's pose without distortion.
  std::vector<std::vector<cv::Point3f>> object(views.size());
  std::vector<std::vector<cv::Point2f>> image(views.size());
  for (size_t v = 0; v < views.size(); ++v) {
    for (size_t i = 0; i < board.size(); ++i) {
      object[v].emplace_back(board[i].x(), board[i].y(), board[i].z());
      image[v].emplace_back(views[v].corners_px[i].x(), views[v].corners_px[i].y());
    }
  }
  const cv::Mat k0 = cv::initCameraMatrix2D(object, image, cv::Size(width, height));
  double focal_centre[4] = {k0.at<double>(0, 0), k0.at<double>(1, 1), k0.at<double>(0, 2),
                            k0.at<double>(1, 2)};
  double k[3] = {0.0, 0.0, 0.0};
  std::vector<std::array<double, 6>> poses(views.size());
  for (size_t v = 0; v < views.size(); ++v) {
    cv::Mat rvec, tvec;
    cv::solvePnP(object[v], image[v], k0, cv::noArray(), rvec, tvec);
    for (int i = 0; i < 3; ++i)
      poses[v][i] = rvec.at<double>(i), poses[v][3 + i] = tvec.at<double>(i);
  }
  ceres::Problem problem;
  for (size_t v = 0; v < views.size(); ++v) {
    for (size_t i = 0; i < board.size(); ++i) {
      auto* cost = new ceres::AutoDiffCostFunction<ReprojectionCost, 2, 4, 3, 3, 3>(
          new ReprojectionCost{board[i], views[v].corners_px[i]});
      problem.AddResidualBlock(cost, nullptr, focal_centre, k, poses[v].data(),
                               poses[v].data() + 3);
    }
  }
  if (options.fix_k3) problem.SetManifold(k, new ceres::SubsetManifold(3, {2}));
  CalibrationResult result;
  std::tie(result.iterations, result.converged) = SolveCalibration(problem, options.max_iterations);
  result.intrinsics = IntrinsicsFrom(focal_centre, k, width, height);
  double total = 0.0;
  for (size_t v = 0; v < views.size(); ++v) {
    result.camera_from_board.push_back(PoseFromAngleAxis(poses[v].data()));
    std::vector<Eigen::Vector2d> residuals;
    double view_sum = 0.0;
    for (size_t i = 0; i < board.size(); ++i) {
      Eigen::Vector2d r;
      ReprojectionCost{board[i], views[v].corners_px[i]}(focal_centre, k, poses[v].data(),
                                                         poses[v].data() + 3, r.data());
      residuals.push_back(-r);  // observed − projected
      view_sum += r.squaredNorm();
    }
    total += view_sum;
    result.view_rms_px.push_back(std::sqrt(view_sum / board.size()));
    result.residuals_px.push_back(std::move(residuals));
  }
  const double points = static_cast<double>(views.size() * board.size());
  result.rms_px = std::sqrt(total / points);
  // Covariance of the intrinsics, scaled by the residual variance per coordinate.
  ceres::Covariance::Options covariance_options;
  ceres::Covariance covariance(covariance_options);
  std::vector<std::pair<const double*, const double*>> blocks{{focal_centre, focal_centre}, {k, k}};
  if (covariance.Compute(blocks, &problem)) {
    const double dof = 2.0 * points - (7.0 - (options.fix_k3 ? 1.0 : 0.0)) - 6.0 * views.size();
    const double variance = dof > 0 ? total / dof : 0.0;
    double cfc[16], ck[9];
    covariance.GetCovarianceBlock(focal_centre, focal_centre, cfc);
    covariance.GetCovarianceBlock(k, k, ck);
    for (int i = 0; i < 4; ++i)
      result.sigma[i] = std::sqrt(std::max(0.0, cfc[i * 4 + i] * variance));
    for (int i = 0; i < 3; ++i)
      result.sigma[4 + i] = std::sqrt(std::max(0.0, ck[i * 3 + i] * variance));
    result.constrained = std::isfinite(result.sigma[0]) &&
                         result.sigma[0] < kMaxRelativeFocalSigma * result.intrinsics.fx;
  }
  return result;
}

int RepeatedView(const std::vector<CalibrationView>& views, const CalibrationView& view,
                 double tolerance_px) {
  for (size_t v = 0; v < views.size(); ++v) {
    if (views[v].corners_px.size() != view.corners_px.size()) continue;
    bool same = true;
    for (size_t i = 0; i < view.corners_px.size() && same; ++i)
      same = (views[v].corners_px[i] - view.corners_px[i]).norm() <= tolerance_px;
    if (same) return static_cast<int>(v);
  }
  return -1;
}

}  // namespace sewer3d
