#pragma once
/// \file
/// Virtual surfaces seen by one module (docs/simulator.md): a plane, the inside of a cylinder,
/// and a pipe-wall patch (cylinder plus wall features). All in the camera frame, mm.

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "sewer3d/sim/material.hpp"
#include "sewer3d/sim/pipe_feature.hpp"

namespace sewer3d {

struct Scene {
  enum class Type { kPlane, kCylinder, kPipeWall };
  Type type = Type::kPlane;
  Material material = Material::kConcrete;
  std::uint64_t material_seed = 1;
  // Plane: crosses the optical axis at distance_mm, normal tilted by tilt_deg about camera x.
  double distance_mm = 140.0;
  double tilt_deg = 0.0;
  // Cylinder / pipe wall: inner diameter, axis direction (camera frame) and the axis's offset
  // from the camera centre (decentring), as a point on the axis.
  double diameter_mm = 300.0;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitY();
  Eigen::Vector3d axis_point_mm = Eigen::Vector3d::Zero();
  /// Pipe wall only: its features, of the pipe world's type and formulas (sim/pipe_feature.hpp);
  /// a pipe-wall scene takes joints (kJointStep), bumps, pits and cracks. Clock positions: 12 h
  /// (= 0 h) is where the camera's optical axis meets the wall, increasing toward camera +x;
  /// stations along the axis from the point nearest the camera.
  std::vector<PipeFeature> features;

  /// Throws InvalidValue naming the field as a scene file does ("features[2].radius_mm").
  void Check() const;
};

/// Where a ray meets the surface.
struct SurfaceHit {
  double t = 0.0;              ///< ray parameter (direction need not be unit)
  Eigen::Vector3d point;       ///< camera frame, mm
  Eigen::Vector3d normal;      ///< unit, facing the ray origin
  Eigen::Vector2d surface_mm;  ///< 2-D surface coordinates for textures (unrolled wall)
  Material material = Material::kConcrete;  ///< what the surface is made of there
  /// Albedo given by the surface itself (a printed target); NaN: from the material.
  Eigen::Vector3d albedo = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  /// Cover of a water film there, 0 (dry) … 1: a specular layer over the wall (wet_film.hpp).
  double film = 0.0;
};

/// First intersection with t > 0 of origin + t * direction; nullopt when the ray misses.
std::optional<SurfaceHit> Intersect(const Scene& scene, const Eigen::Vector3d& origin,
                                    const Eigen::Vector3d& direction);

/// Distance (mm) from a camera-frame point to the surface: exact for planes and cylinders;
/// for a pipe wall, the shortest distance to the displaced wall profile within ±3 mm along the
/// axis and around it (0.05 mm samples), vertical faces of steps included.
double DistanceToSurfaceMm(const Scene& scene, const Eigen::Vector3d& point);

/// Radial displacement of the pipe wall toward the axis (mm) at a clock angle and station.
double WallDisplacementMm(const Scene& scene, double clock_rad, double station_mm);

}  // namespace sewer3d
