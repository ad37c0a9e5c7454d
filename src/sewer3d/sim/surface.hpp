#pragma once
/// \file
/// What the renderer looks at: any surface that answers ray queries in the camera frame.

#include <Eigen/Core>
#include <cstdint>
#include <optional>

#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/sim/pipe_world.hpp"
#include "sewer3d/sim/scene.hpp"

namespace sewer3d {

class Surface {
 public:
  virtual ~Surface() = default;
  /// First hit with t > 0 of origin + t * direction (camera frame), or nullopt.
  virtual std::optional<SurfaceHit> Intersect(const Eigen::Vector3d& origin,
                                              const Eigen::Vector3d& direction) const = 0;
  virtual std::uint64_t MaterialSeed() const = 0;
};

/// A single-module scene (plane, cylinder, pipe-wall patch) given in the camera frame.
class SceneSurface final : public Surface {
 public:
  explicit SceneSurface(const Scene& scene) : scene_(scene) {}
  std::optional<SurfaceHit> Intersect(const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& direction) const override {
    return sewer3d::Intersect(scene_, origin, direction);
  }
  std::uint64_t MaterialSeed() const override { return scene_.material_seed; }

 private:
  const Scene& scene_;
};

/// The pipe world seen from a camera at a pose.
class PipeView final : public Surface {
 public:
  PipeView(const PipeGeometry& pipe, const Rigid3d& world_from_camera)
      : pipe_(pipe),
        world_from_camera_(world_from_camera),
        camera_from_world_(world_from_camera.Inverse()) {}
  std::optional<SurfaceHit> Intersect(const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& direction) const override {
    auto hit =
        pipe_.Intersect(world_from_camera_ * origin, world_from_camera_.rotation * direction);
    if (hit) {
      hit->point = camera_from_world_ * hit->point;
      hit->normal = camera_from_world_.rotation * hit->normal;
    }
    return hit;
  }
  std::uint64_t MaterialSeed() const override { return pipe_.world().material_seed; }

 private:
  const PipeGeometry& pipe_;
  Rigid3d world_from_camera_, camera_from_world_;
};

}  // namespace sewer3d
