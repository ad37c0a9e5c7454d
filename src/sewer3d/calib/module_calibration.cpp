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

bool ModuleCalibrationView::Complete() const {
  return std::all_of(projector_corners.begin(), projector_corners.end(),
                     [](const Eigen::Vector2d& c) { return c.allFinite(); });
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
    bool all = true;
    for (size_t i = 0; i < again.size(); ++i) {
      if (again[i]) {
        views[v].projector_corners[i] = *again[i];
      } else if (views[v].projector_corners[i].allFinite()) {
        all = false;
      }
    }
    if (all) ++updated;
  }
  return updated;
}

namespace {

// Floor of a device's corner noise in the weights (exact synthetic corners have none).
constexpr double kMinNoisePx = 0.01;

// The joint problem's parameters: both devices' intrinsics, the extrinsics, every view's pose.
struct StereoParameters {
  double camera_fc[4], camera_k[3], projector_fc[4], projector_k[3];
  std::array<double, 6> extrinsic;
  std::vector<std::array<double, 6>> poses;

  // One view's corner residuals (px) on the camera and, where carried, on the projector.
  Eigen::Vector2d CameraResidual(const Eigen::Vector3d& corner, const Eigen::Vector2d& px,
                                 size_t v) const {
    Eigen::Vector2d r;
    ReprojectionCost{corner, px}(camera_fc, camera_k, poses[v].data(), poses[v].data() + 3,
                                 r.data());
    return r;
  }
  Eigen::Vector2d ProjectorResidual(const Eigen::Vector3d& corner, const Eigen::Vector2d& px,
                                    size_t v) const {
    Eigen::Vector2d r;
    StereoReprojectionCost{corner, px}(projector_fc, projector_k, poses[v].data(),
                                       poses[v].data() + 3, extrinsic.data(), extrinsic.data() + 3,
                                       r.data());
    return r;
  }
};

// Each device's corners weighted by 1 / its noise (px): the projector's corners, carried by
// homographies from spots that scatter, are several times noisier than the camera's.
void AddStereoResiduals(ceres::Problem& problem, const std::vector<ModuleCalibrationView>& views,
                        const std::vector<Eigen::Vector3d>& board, StereoParameters& x,
                        double camera_noise_px, double projector_noise_px) {
  for (size_t v = 0; v < views.size(); ++v) {
    double* pose = x.poses[v].data();
    for (size_t i = 0; i < board.size(); ++i) {
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<ReprojectionCost, 2, 4, 3, 3, 3>(
              new ReprojectionCost{board[i], views[v].camera_corners[i], 1.0 / camera_noise_px}),
          nullptr, x.camera_fc, x.camera_k, pose, pose + 3);
      if (!views[v].projector_corners[i].allFinite()) continue;  // not carried
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<StereoReprojectionCost, 2, 4, 3, 3, 3, 3, 3>(
              new StereoReprojectionCost{board[i], views[v].projector_corners[i],
                                         1.0 / projector_noise_px}),
          nullptr, x.projector_fc, x.projector_k, pose, pose + 3, x.extrinsic.data(),
          x.extrinsic.data() + 3);
    }
  }
}

// A carried corner can be wrong by whole pattern pitches (a group of spots decoded with the
// wrong label carries it consistently): projector corners whose residual exceeds five times
// the projector RMS (at least 2 px) are dropped. Returns how many.
int DropProjectorOutliers(std::vector<ModuleCalibrationView>& views,
                          const std::vector<Eigen::Vector3d>& board, const StereoParameters& x,
                          double projector_rms_px) {
  const double limit = std::max(2.0, 5.0 * projector_rms_px);
  int dropped = 0;
  for (size_t v = 0; v < views.size(); ++v) {
    for (size_t i = 0; i < board.size(); ++i) {
      Eigen::Vector2d& corner = views[v].projector_corners[i];
      if (!corner.allFinite() || x.ProjectorResidual(board[i], corner, v).norm() <= limit) continue;
      corner = Eigen::Vector2d::Constant(std::nan(""));
      ++dropped;
    }
  }
  return dropped;
}

// Per-view and overall RMS of the solved problem.
void SetResiduals(const std::vector<ModuleCalibrationView>& views,
                  const std::vector<Eigen::Vector3d>& board, const StereoParameters& x,
                  ModuleCalibrationResult& r, double& camera_total, double& projector_total,
                  double& projector_points) {
  camera_total = projector_total = projector_points = 0.0;
  r.view_camera_rms_px.clear();
  r.view_projector_rms_px.clear();
  for (size_t v = 0; v < views.size(); ++v) {
    double cs = 0.0, ps = 0.0;
    int carried = 0;
    for (size_t i = 0; i < board.size(); ++i) {
      cs += x.CameraResidual(board[i], views[v].camera_corners[i], v).squaredNorm();
      if (!views[v].projector_corners[i].allFinite()) continue;
      ps += x.ProjectorResidual(board[i], views[v].projector_corners[i], v).squaredNorm();
      ++carried;
    }
    camera_total += cs;
    projector_total += ps;
    projector_points += carried;
    r.view_camera_rms_px.push_back(std::sqrt(cs / board.size()));
    r.view_projector_rms_px.push_back(std::sqrt(ps / std::max(1, carried)));
  }
  r.camera_rms_px = std::sqrt(camera_total / static_cast<double>(views.size() * board.size()));
  r.projector_rms_px = std::sqrt(projector_total / std::max(1.0, projector_points));
}

}  // namespace

ModuleCalibrationResult CalibrateModule(const std::vector<ModuleCalibrationView>& views,
                                        const std::vector<Eigen::Vector3d>& board, int camera_width,
                                        int camera_height, int projector_width,
                                        int projector_height) {
  // Each device alone first (Zhang + refinement; the projector from its complete views), then
  // both together.
  std::vector<CalibrationView> camera_views, projector_views;
  size_t first_complete = views.size();
  for (size_t v = 0; v < views.size(); ++v) {
    camera_views.push_back({views[v].camera_corners});
    if (!views[v].Complete()) continue;
    projector_views.push_back({views[v].projector_corners});
    first_complete = std::min(first_complete, v);
  }
  SEWER3D_VALIDATE(projector_views.size() >= 3, "",
                   "module calibration needs at least 3 views with every corner carried into "
                   "the projector, got "
                       << projector_views.size());
  const CalibrationResult camera =
      CalibrateCamera(camera_views, board, camera_width, camera_height);
  const CalibrationResult projector =
      CalibrateCamera(projector_views, board, projector_width, projector_height);
  StereoParameters x{};
  const CameraIntrinsics& c = camera.intrinsics;
  const CameraIntrinsics& p = projector.intrinsics;
  std::copy_n(std::array<double, 4>{c.fx, c.fy, c.cx, c.cy}.begin(), 4, x.camera_fc);
  std::copy_n(c.k.begin(), 3, x.camera_k);
  std::copy_n(std::array<double, 4>{p.fx, p.fy, p.cx, p.cy}.begin(), 4, x.projector_fc);
  std::copy_n(p.k.begin(), 3, x.projector_k);
  // Extrinsics: the first complete view's projector_from_board · board_from_camera.
  x.extrinsic = AngleAxisOf(projector.camera_from_board[0] *
                            camera.camera_from_board[first_complete].Inverse());
  for (const Rigid3d& pose : camera.camera_from_board) x.poses.push_back(AngleAxisOf(pose));
  // Solved again without the projector corners the solution shows to be wrong, and with each
  // device's weight from the last solution's RMS (first: from each device alone).
  std::vector<ModuleCalibrationView> kept = views;
  double camera_noise = std::max(kMinNoisePx, camera.rms_px);
  double projector_noise = std::max(kMinNoisePx, projector.rms_px);
  ModuleCalibrationResult r;
  double camera_total = 0.0, projector_total = 0.0, projector_points = 0.0;
  for (int round = 0;; ++round) {
    ceres::Problem attempt;
    AddStereoResiduals(attempt, kept, board, x, camera_noise, projector_noise);
    std::tie(r.iterations, r.converged) = SolveCalibration(attempt, 200);
    SetResiduals(kept, board, x, r, camera_total, projector_total, projector_points);
    const int dropped = round == 3 ? 0 : DropProjectorOutliers(kept, board, x, r.projector_rms_px);
    // The weights of the next round from the corners it keeps.
    if (dropped > 0)
      SetResiduals(kept, board, x, r, camera_total, projector_total, projector_points);
    const bool settled = std::abs(r.projector_rms_px / projector_noise - 1.0) < 0.1 &&
                         std::abs(r.camera_rms_px / camera_noise - 1.0) < 0.1;
    camera_noise = std::max(kMinNoisePx, r.camera_rms_px);
    projector_noise = std::max(kMinNoisePx, r.projector_rms_px);
    if (round == 3 || (dropped == 0 && settled)) break;
  }
  ceres::Problem problem;  // the last one, for the covariance
  AddStereoResiduals(problem, kept, board, x, camera_noise, projector_noise);
  r.camera = IntrinsicsFrom(x.camera_fc, x.camera_k, camera_width, camera_height);
  r.projector = IntrinsicsFrom(x.projector_fc, x.projector_k, projector_width, projector_height);
  r.projector_from_camera = PoseFromAngleAxis(x.extrinsic.data());
  // Uncertainties from the covariance, scaled by the residual variance per coordinate.
  ceres::Covariance covariance({});
  const std::vector<std::pair<const double*, const double*>> blocks{
      {x.camera_fc, x.camera_fc},
      {x.projector_fc, x.projector_fc},
      {x.extrinsic.data(), x.extrinsic.data()},
      {x.extrinsic.data() + 3, x.extrinsic.data() + 3}};
  if (covariance.Compute(blocks, &problem)) {
    const double camera_points = static_cast<double>(views.size() * board.size());
    const double dof = 2.0 * (camera_points + projector_points) - 20.0 - 6.0 * views.size();
    // The weighted residuals' variance (about 1 when the weights are the devices' noise).
    const double weighted = camera_total / (camera_noise * camera_noise) +
                            projector_total / (projector_noise * projector_noise);
    const double variance = dof > 0 ? weighted / dof : 0.0;
    double c4[16], p4[16], rot[9], tr[9];
    covariance.GetCovarianceBlock(x.camera_fc, x.camera_fc, c4);
    covariance.GetCovarianceBlock(x.projector_fc, x.projector_fc, p4);
    covariance.GetCovarianceBlock(x.extrinsic.data(), x.extrinsic.data(), rot);
    covariance.GetCovarianceBlock(x.extrinsic.data() + 3, x.extrinsic.data() + 3, tr);
    for (int i = 0; i < 4; ++i) {
      r.sigma[i] = std::sqrt(std::max(0.0, c4[i * 5] * variance));
      r.sigma[4 + i] = std::sqrt(std::max(0.0, p4[i * 5] * variance));
    }
    // Baseline length |t|: σ² = tᵀ Σ t / |t|².
    const Eigen::Vector3d t(x.extrinsic[3], x.extrinsic[4], x.extrinsic[5]);
    const Eigen::Matrix3d st = Eigen::Map<const Eigen::Matrix3d>(tr) * variance;
    r.sigma[8] = std::sqrt(std::max(0.0, t.dot(st * t))) / std::max(1e-12, t.norm());
    r.sigma[9] = RadToDeg(std::sqrt(std::max({rot[0], rot[4], rot[8], 0.0}) * variance));
  }
  return r;
}

}  // namespace sewer3d
