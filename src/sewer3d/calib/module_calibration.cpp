#include "sewer3d/calib/module_calibration.hpp"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <tuple>

#include "sewer3d/calib/camera_calibration.hpp"
#include "sewer3d/calib/reprojection.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"

namespace sewer3d {

std::vector<std::optional<Eigen::Vector2d>> CornersInProjector(
    const std::vector<Eigen::Vector2d>& corners, const std::vector<Eigen::Vector2d>& camera_px,
    const std::vector<Eigen::Vector2d>& projector_px, const CornerTransferOptions& o) {
  SEWER3D_CHECK(camera_px.size() == projector_px.size(), "spot correspondences");
  SEWER3D_CHECK(o.camera.has_value() == o.projector.has_value(),
                "corner transfer: camera and projector models go together");
  // Coordinates of the fit: pixels, or undistorted normalised coordinates of both devices.
  std::optional<CameraModel> camera, projector;
  double threshold = o.ransac_px;
  if (o.camera) {
    camera.emplace(*o.camera);
    projector.emplace(*o.projector);
    threshold = o.ransac_px / o.projector->fx;
  }
  const auto to_fit = [](const std::optional<CameraModel>& model,
                         const Eigen::Vector2d& px) -> std::optional<Eigen::Vector2d> {
    return model ? model->Unproject(px) : std::optional<Eigen::Vector2d>(px);
  };
  std::vector<std::optional<Eigen::Vector2d>> out;
  std::vector<cv::Point2d> src, dst;
  for (const Eigen::Vector2d& corner : corners) {
    src.clear();
    dst.clear();
    for (size_t i = 0; i < camera_px.size(); ++i) {
      if ((camera_px[i] - corner).squaredNorm() > o.radius_px * o.radius_px) continue;
      const auto a = to_fit(camera, camera_px[i]);
      const auto b = to_fit(projector, projector_px[i]);
      if (!a || !b) continue;
      src.emplace_back(a->x(), a->y());
      dst.emplace_back(b->x(), b->y());
    }
    const auto c = to_fit(camera, corner);
    if (static_cast<int>(src.size()) < o.min_spots || !c) {
      out.emplace_back();
      continue;
    }
    cv::Mat inliers;
    const cv::Mat h = cv::findHomography(src, dst, cv::RANSAC, threshold, inliers);
    if (h.empty() || cv::countNonZero(inliers) < o.min_spots) {
      out.emplace_back();
      continue;
    }
    Eigen::Matrix3d hm;
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) hm(r, k) = h.at<double>(r, k);
    const Eigen::Vector3d q = hm * c->homogeneous();
    if (!projector) {
      out.emplace_back(q.head<2>() / q.z());
    } else {
      out.push_back(projector->Project(q / q.z()));
    }
  }
  return out;
}

int RetransferCorners(std::vector<ModuleCalibrationView>& views,
                      const std::vector<SpotCorrespondences>& spots, const CameraIntrinsics& camera,
                      const CameraIntrinsics& projector, const CornerTransferOptions& options) {
  SEWER3D_CHECK(views.size() == spots.size(), "one spot set per view");
  CornerTransferOptions undistorted = options;
  undistorted.camera = camera;
  undistorted.projector = projector;
  int updated = 0;
  for (size_t v = 0; v < views.size(); ++v) {
    const auto again = CornersInProjector(views[v].camera_corners, spots[v].camera_px,
                                          spots[v].projector_px, undistorted);
    if (!std::all_of(again.begin(), again.end(), [](const auto& c) { return c.has_value(); }))
      continue;
    for (size_t i = 0; i < again.size(); ++i) views[v].projector_corners[i] = *again[i];
    ++updated;
  }
  return updated;
}

ModuleCalibrationResult CalibrateModule(const std::vector<ModuleCalibrationView>& views,
                                        const std::vector<Eigen::Vector3d>& board, int camera_width,
                                        int camera_height, int projector_width,
                                        int projector_height) {
  SEWER3D_VALIDATE(views.size() >= 3, "",
                   "module calibration needs at least 3 views, got " << views.size());
  // Each device alone first (Zhang + refinement), then both together.
  std::vector<CalibrationView> camera_views, projector_views;
  for (const auto& v : views) {
    camera_views.push_back({v.camera_corners});
    projector_views.push_back({v.projector_corners});
  }
  const CalibrationResult camera =
      CalibrateCamera(camera_views, board, camera_width, camera_height);
  const CalibrationResult projector =
      CalibrateCamera(projector_views, board, projector_width, projector_height);
  // Extrinsics: the first view's projector_from_board · board_from_camera.
  const Rigid3d extrinsic0 = projector.camera_from_board[0] * camera.camera_from_board[0].Inverse();

  double camera_fc[4] = {camera.intrinsics.fx, camera.intrinsics.fy, camera.intrinsics.cx,
                         camera.intrinsics.cy};
  double camera_k[3] = {camera.intrinsics.k[0], camera.intrinsics.k[1], camera.intrinsics.k[2]};
  double projector_fc[4] = {projector.intrinsics.fx, projector.intrinsics.fy,
                            projector.intrinsics.cx, projector.intrinsics.cy};
  double projector_k[3] = {projector.intrinsics.k[0], projector.intrinsics.k[1],
                           projector.intrinsics.k[2]};
  std::array<double, 6> extrinsic = AngleAxisOf(extrinsic0);
  std::vector<std::array<double, 6>> poses;
  for (const Rigid3d& p : camera.camera_from_board) poses.push_back(AngleAxisOf(p));
  ceres::Problem problem;
  for (size_t v = 0; v < views.size(); ++v) {
    for (size_t i = 0; i < board.size(); ++i) {
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<ReprojectionCost, 2, 4, 3, 3, 3>(
                                   new ReprojectionCost{board[i], views[v].camera_corners[i]}),
                               nullptr, camera_fc, camera_k, poses[v].data(), poses[v].data() + 3);
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<StereoReprojectionCost, 2, 4, 3, 3, 3, 3, 3>(
              new StereoReprojectionCost{board[i], views[v].projector_corners[i]}),
          nullptr, projector_fc, projector_k, poses[v].data(), poses[v].data() + 3,
          extrinsic.data(), extrinsic.data() + 3);
    }
  }
  ModuleCalibrationResult r;
  std::tie(r.iterations, r.converged) = SolveCalibration(problem, 200);
  r.camera = IntrinsicsFrom(camera_fc, camera_k, camera_width, camera_height);
  r.projector = IntrinsicsFrom(projector_fc, projector_k, projector_width, projector_height);
  r.projector_from_camera = PoseFromAngleAxis(extrinsic.data());
  double camera_total = 0.0, projector_total = 0.0;
  for (size_t v = 0; v < views.size(); ++v) {
    double cs = 0.0, ps = 0.0;
    for (size_t i = 0; i < board.size(); ++i) {
      Eigen::Vector2d rc, rp;
      ReprojectionCost{board[i], views[v].camera_corners[i]}(camera_fc, camera_k, poses[v].data(),
                                                             poses[v].data() + 3, rc.data());
      StereoReprojectionCost{board[i], views[v].projector_corners[i]}(
          projector_fc, projector_k, poses[v].data(), poses[v].data() + 3, extrinsic.data(),
          extrinsic.data() + 3, rp.data());
      cs += rc.squaredNorm();
      ps += rp.squaredNorm();
    }
    camera_total += cs;
    projector_total += ps;
    r.view_camera_rms_px.push_back(std::sqrt(cs / board.size()));
    r.view_projector_rms_px.push_back(std::sqrt(ps / board.size()));
  }
  const double points = static_cast<double>(views.size() * board.size());
  r.camera_rms_px = std::sqrt(camera_total / points);
  r.projector_rms_px = std::sqrt(projector_total / points);
  // Uncertainties from the covariance, scaled by the residual variance per coordinate.
  ceres::Covariance covariance({});
  const std::vector<std::pair<const double*, const double*>> blocks{
      {camera_fc, camera_fc},
      {projector_fc, projector_fc},
      {extrinsic.data(), extrinsic.data()},
      {extrinsic.data() + 3, extrinsic.data() + 3}};
  if (covariance.Compute(blocks, &problem)) {
    const double dof = 4.0 * points - 20.0 - 6.0 * views.size();
    const double variance = dof > 0 ? (camera_total + projector_total) / dof : 0.0;
    double c4[16], p4[16], rot[9], tr[9];
    covariance.GetCovarianceBlock(camera_fc, camera_fc, c4);
    covariance.GetCovarianceBlock(projector_fc, projector_fc, p4);
    covariance.GetCovarianceBlock(extrinsic.data(), extrinsic.data(), rot);
    covariance.GetCovarianceBlock(extrinsic.data() + 3, extrinsic.data() + 3, tr);
    for (int i = 0; i < 4; ++i) {
      r.sigma[i] = std::sqrt(std::max(0.0, c4[i * 5] * variance));
      r.sigma[4 + i] = std::sqrt(std::max(0.0, p4[i * 5] * variance));
    }
    // Baseline length |t|: σ² = tᵀ Σ t / |t|².
    const Eigen::Vector3d t(extrinsic[3], extrinsic[4], extrinsic[5]);
    const Eigen::Matrix3d st = Eigen::Map<const Eigen::Matrix3d>(tr) * variance;
    r.sigma[8] = std::sqrt(std::max(0.0, t.dot(st * t))) / std::max(1e-12, t.norm());
    r.sigma[9] = RadToDeg(std::sqrt(std::max({rot[0], rot[4], rot[8], 0.0}) * variance));
  }
  return r;
}

}  // namespace sewer3d
