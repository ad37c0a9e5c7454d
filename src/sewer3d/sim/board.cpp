#include "sewer3d/sim/board.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/sim/material.hpp"

namespace sewer3d {

void Checkerboard::Check() const {
  SEWER3D_VALIDATE(cols >= 2 && rows >= 2, "board",
                   "needs at least 2x2 inner corners, got " << cols << "x" << rows);
  ValidatePositive("square_mm", square_mm);
  ValidateNotNegative("margin_mm", margin_mm);
}

std::optional<SurfaceHit> BoardSurface::Intersect(const Eigen::Vector3d& origin,
                                                  const Eigen::Vector3d& direction) const {
  const Eigen::Vector3d o = board_from_camera_ * origin,
                        d = board_from_camera_.rotation * direction;
  if (std::abs(d.z()) < 1e-15) return std::nullopt;
  const double t = -o.z() / d.z();
  if (!(t > 0.0)) return std::nullopt;
  const Eigen::Vector3d p = o + t * d;
  const double s = board_.square_mm, m = board_.margin_mm;
  if (p.x() < -s - m || p.y() < -s - m || p.x() > board_.cols * s + m ||
      p.y() > board_.rows * s + m) {
    return std::nullopt;  // off the plate
  }
  SurfaceHit hit;
  hit.t = t;
  hit.point = origin + t * direction;
  const Eigen::Vector3d normal = camera_from_board_.rotation * Eigen::Vector3d::UnitZ();
  hit.normal = normal.dot(direction) < 0.0 ? normal : -normal;
  hit.surface_mm = p.head<2>();
  const bool checker =
      p.x() >= -s && p.y() >= -s && p.x() <= board_.cols * s && p.y() <= board_.rows * s;
  const bool black =
      checker &&
      (static_cast<long>(std::floor(p.x() / s)) + static_cast<long>(std::floor(p.y() / s))) % 2 ==
          0;
  hit.albedo = Eigen::Vector3d::Constant(black ? 0.05 : 0.85);
  return hit;
}

std::vector<Rigid3d> RandomBoardPoses(const ModuleDescription& module, const Checkerboard& board,
                                      int count, std::uint64_t seed, const BoardPoseOptions& o) {
  board.Check();
  module.Check();
  SEWER3D_VALIDATE(count >= 1, "poses", "must be at least 1, got " << count);
  const double square_px =
      std::min(module.camera.fx, module.camera.fy) * board.square_mm / o.distance_max_mm;
  SEWER3D_VALIDATE(square_px >= o.min_square_px, "square_mm",
                   board.square_mm << " mm squares look " << square_px << " px wide at "
                                   << o.distance_max_mm << " mm, too small to detect; at least "
                                   << o.min_square_px * o.distance_max_mm /
                                          std::min(module.camera.fx, module.camera.fy)
                                   << " mm");
  const CameraModel camera(module.camera), projector(module.projector);
  const Eigen::Vector3d centre(0.5 * (board.cols - 1) * board.square_mm,
                               0.5 * (board.rows - 1) * board.square_mm, 0.0);
  auto inside = [&](const std::optional<Eigen::Vector2d>& uv, int w, int h) {
    return uv && uv->x() >= o.margin_px && uv->y() >= o.margin_px &&
           uv->x() <= w - 1 - o.margin_px && uv->y() <= h - 1 - o.margin_px;
  };
  std::vector<Rigid3d> poses;
  for (std::uint64_t attempt = 0; static_cast<int>(poses.size()) < count; ++attempt) {
    SEWER3D_VALIDATE(attempt < 200000, "board",
                     "no pose shows the whole board ("
                         << board.cols << " x " << board.rows << " squares of " << board.square_mm
                         << " mm) to both camera and projector (try fewer or smaller squares)");
    auto u = [&](int k) { return HashUniform(seed, attempt, k); };
    // Board centre on a random camera ray through the image, at a random depth.
    const auto xy =
        camera.Unproject({u(0) * (module.camera.width - 1), u(1) * (module.camera.height - 1)});
    if (!xy) continue;
    const double depth = o.distance_min_mm + u(2) * (o.distance_max_mm - o.distance_min_mm);
    const Eigen::Vector3d target = Eigen::Vector3d(xy->x(), xy->y(), 1.0) * depth;
    // Facing the camera (board z away from it), tilted about a random in-plane axis, spun.
    const double tilt = std::acos(1.0 - u(3) * (1.0 - std::cos(DegToRad(o.max_tilt_deg))));
    const double axis_angle = kTwoPi * u(4), spin = kTwoPi * u(5);
    const Eigen::Quaterniond rotation =
        Eigen::AngleAxisd(tilt, Eigen::Vector3d(std::cos(axis_angle), std::sin(axis_angle), 0.0)) *
        Eigen::AngleAxisd(spin, Eigen::Vector3d::UnitZ());
    const Rigid3d pose(rotation, target - rotation * centre);
    bool ok = true;
    for (int i = 0; i < board.rows && ok; ++i) {
      for (int j = 0; j < board.cols && ok; ++j) {
        const Eigen::Vector3d p =
            pose * Eigen::Vector3d(j * board.square_mm, i * board.square_mm, 0.0);
        ok = inside(camera.Project(p), module.camera.width, module.camera.height) &&
             inside(projector.Project(module.projector_from_camera * p), module.projector.width,
                    module.projector.height);
      }
    }
    if (ok) poses.push_back(pose);
  }
  return poses;
}

}  // namespace sewer3d
