#pragma once
/// \file
/// The pipe world of a virtual inspection run (docs/simulator.md, "Pipe world"): a chain of
/// pipe sections (material, diameter, deformation, gentle bends) joined by joints (gap,
/// radial offset, angular deflection), with wall features (intruding connections, spalling,
/// cracks, deposits). World frame: z along the start of the pipe (direction of travel), y down,
/// x to the right looking along z. Stations are mm along the centreline from the pipe start;
/// clock positions are in hours as in EN 13508-2 (12 = crown, 3 = right looking downstream).

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/core/units.hpp"
#include "sewer3d/sim/pipe_feature.hpp"
#include "sewer3d/sim/scene.hpp"

namespace sewer3d {

struct PipeSection {
  double length_mm = 1000.0;
  double diameter_mm = 300.0;  ///< inner diameter
  Material material = Material::kConcrete;
  /// Deformation (EN 13508-2 BAA): the diameter toward ovality_clock_h is reduced by this
  /// percentage and the one at right angles enlarged by it; ramps in over the section ends.
  double ovality_pct = 0.0;
  double ovality_clock_h = 12.0;
  double bend_radius_mm = 0.0;  ///< 0: straight; otherwise the centreline's radius of curvature
  double bend_clock_h = 3.0;    ///< the direction toward which the pipe turns
};

/// The joint at the end of a section (between section i and i + 1).
struct PipeJoint {
  std::string id;
  double gap_mm = 0.0;        ///< open gap width along the axis
  double gap_depth_mm = 0.0;  ///< depth of the gap into the wall
  /// Radial offset (BAJ B): the next section's wall toward offset_clock_h is this much inward.
  double offset_mm = 0.0;
  double offset_clock_h = 12.0;
  /// Angular deflection (BAJ C): the next section's axis is turned toward deflection_clock_h.
  double deflection_deg = 0.0;
  double deflection_clock_h = 3.0;
};

struct PipeWorld {
  static constexpr double kMaxLengthMm = 2.0e6;  ///< 2 km: longer than any manhole-to-manhole run
  std::vector<PipeSection> sections;
  std::vector<PipeJoint> joints;  ///< sections.size() - 1
  /// Wall features (sim/pipe_feature.hpp): connections, spalling, cracks and deposits.
  std::vector<PipeFeature> features;
  std::uint64_t material_seed = 1;

  /// Throws InvalidValue naming the field as the scenario file's "pipe" does ("joints").
  void Check() const;
  /// Every joint and feature id differs (truth files name them by id).
  void CheckUniqueIds() const;
  /// No two features of a type in one place (within 1 mm and 0.05 h), no two connections whose
  /// holes (with their walls) meet on a wall of `radius_mm`.
  void CheckFeaturesApart(double radius_mm) const;
  /// The whole feature lies on the pipe: its reach along it within 0 .. LengthMm(), its span
  /// around it within the circumference of the smallest section (`smallest`, a diameter).
  void CheckFeatureOnPipe(const PipeFeature& f, const std::string& field, double smallest) const;
  double LengthMm() const;
};

/// Where a world point lies relative to the pipe.
struct PipeLocation {
  int section = 0;
  double station_mm = 0.0;  ///< along the centreline (section start station + local arc)
  double local_mm = 0.0;    ///< along the section's own centreline from its start
  double clock_rad = 0.0;   ///< 0 at the crown, increasing clockwise looking downstream
  double rho_mm = 0.0;      ///< distance from the section's centreline
  Eigen::Vector2d radial = Eigen::Vector2d::Zero();  ///< (x, y) in the centreline frame
};

/// The geometry of a PipeWorld: section frames, point location, wall radius, ray hits.
class PipeGeometry {
 public:
  explicit PipeGeometry(PipeWorld world);  ///< checks the world

  const PipeWorld& world() const { return world_; }
  double SectionStartMm(int i) const { return start_station_[i]; }

  /// Centreline frame of a section at a local arc length (extrapolated outside the section):
  /// origin on the centreline, z the tangent, −y toward 12 o'clock.
  Rigid3d SectionFrame(int section, double local_mm) const;
  /// A smooth path for a robot: the centreline frame at a station, blended over ±blend_mm
  /// across each joint so that offsets and deflections do not make the path jump.
  Rigid3d PathFrame(double station_mm, double blend_mm = 100.0) const;

  PipeLocation Locate(const Eigen::Vector3d& p_world) const;
  /// Distance of the wall from the section's centreline at a location (deformation and
  /// features included).
  double WallRadiusMm(const PipeLocation& at) const;
  /// ρ − wall radius: negative inside the pipe.
  double SignedDistanceMm(const Eigen::Vector3d& p_world) const;
  /// First wall hit of a ray from a point inside the pipe (world frame); the hit carries the
  /// material there and unrolled surface coordinates (arc mm, station mm).
  std::optional<SurfaceHit> Intersect(const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& direction) const;

 private:
  PipeLocation LocateAt(const Eigen::Vector3d& p_world, bool with_clock) const;
  double Displacement(PipeLocation at, Material* material) const;

  PipeWorld world_;
  std::vector<double> start_station_;
  std::vector<Rigid3d> section_start_;                   ///< world_from_section at local 0
  std::vector<Eigen::Matrix3d> start_inverse_rotation_;  ///< section_from_world, for speed
  std::vector<Eigen::Vector3d> start_inverse_translation_;
  std::vector<Eigen::Vector3d> joint_point_, joint_normal_;  ///< bisecting planes
};

/// Direction of a clock position in a centreline frame (unit, z = 0).
Eigen::Vector3d ClockDirection(double clock_rad);

}  // namespace sewer3d
