#pragma once
/// \file
/// Wall features of the simulated pipes: local displacements of the wall along its radius,
/// placed by station along the pipe and clock position around it. One type and one set of
/// formulas for both descriptions of a pipe: the pipe world of a run (sim/pipe_world.hpp) and
/// the single-frame pipe-wall scene (sim/scene.hpp). The formulas are given in
/// docs/simulated_run.md ("Pipe world") and docs/simulator.md ("Scenes").

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <span>
#include <string>

#include "sewer3d/core/units.hpp"
#include "sewer3d/sim/material.hpp"

namespace sewer3d {

/// A wall feature. Displacements are toward the pipe axis (positive: the wall comes closer):
/// `height_mm` measures what rises out of the wall, `depth_mm` what goes into it.
struct PipeFeature {
  enum class Type {
    kConnection,  ///< intruding lateral connection (EN 13508-2 BAG); pipe worlds
    kSpalling,    ///< spalled patch, rough bottom (BAF); pipe worlds
    kCrack,       ///< V-shaped groove (BAB); pipe worlds and pipe-wall scenes
    kDeposit,     ///< sediment bed at the invert (BBC); pipe worlds
    kBump,        ///< Gaussian intrusion; pipe-wall scenes
    kPit,         ///< paraboloid pit; pipe-wall scenes
    /// A joint drawn on one cylinder (an open gap, and the wall beyond it displaced by
    /// offset · cos(clock − clock₀)); pipe-wall scenes. A pipe world's joints are PipeJoint,
    /// between its sections.
    kJointStep,
    /// A water film on the wall (infiltration seeping through it, EN 13508-2 BBF A; a wetted
    /// invert): no displacement; the renderer adds its gloss (wet_film.hpp). Pipe worlds and
    /// pipe-wall scenes.
    kWet,
  };
  Type type = Type::kConnection;
  std::string id = {};        ///< name in truth files (scenario features: F1, F2, … unless given)
  double station_mm = 0.0;    ///< centre (deposit: start; joint step: centre of the gap)
  double clock_h = 12.0;      ///< centre (deposit: lowest point, normally 6); 12 h = one turn
  double diameter_mm = 0.0;   ///< connection: inner diameter of the lateral pipe
  double wall_mm = 0.0;       ///< connection: wall thickness of the lateral pipe
  double intrusion_mm = 0.0;  ///< connection: how far the lateral's end protrudes (BAG)
  double length_mm = 0.0;     ///< spalling / crack / deposit / wet: extent along the pipe
  double width_mm = 0.0;      ///< spalling / wet: extent around the pipe; crack: opening
  double depth_mm = 0.0;      ///< spalling / crack / pit: depth into the wall; joint step: gap
  double height_mm = 0.0;     ///< deposit: height above the invert (BBC); bump: height
  double angle_deg = 0.0;     ///< crack: direction on the unrolled wall (0 = along the pipe)
  double gap_mm = 0.0;        ///< joint step: width of the open gap along the pipe
  double offset_mm = 0.0;     ///< joint step: the wall beyond the gap moved inward at clock_h
  double radius_mm = 0.0;     ///< bump: Gaussian sigma; pit: radius

  /// Validates the dimensions this kind needs; throws InvalidValue naming the field
  /// ("length_mm", …) relative to the feature.
  void Check() const;
  /// Check() and the dimensions against a pipe of this inner diameter: depths under a fifth of
  /// it, heights under half, bump and pit radii and connection diameters under the diameter.
  void CheckInPipe(double pipe_diameter_mm) const;
  /// At most this many features in one scene or pipe (each sample of the wall visits them).
  static constexpr std::size_t kMaxCount = 5000;
};

/// The feature kind's name in scene and scenario files: "connection", "spalling", "crack",
/// "deposit", "bump", "pit", "joint", "wet".
const char* PipeFeatureTypeName(PipeFeature::Type type);

/// The kind a scene or scenario file names `name`; nullopt for an unknown name.
std::optional<PipeFeature::Type> PipeFeatureTypeFromName(const std::string& name);

/// A bump ends this many sigmas from its centre (along and around the pipe), where its
/// Gaussian has fallen to e^-32 of its height: a scene of many bumps visits only the near ones.
inline constexpr double kBumpReachSigmas = 8.0;

/// Distance along the pipe from the feature's station beyond which it leaves the wall alone
/// (infinite for joint steps).
double PipeFeatureReachMm(const PipeFeature& f);

/// Displacement (mm, toward the axis) of one feature at a wall point `ds_mm` along the pipe
/// from its station and `dclock_rad` around from its clock (in [−π, π]), on a wall of nominal
/// radius `radius_mm`. `noise_seed` seeds rough surfaces; `own_material` is set where the
/// feature has a material of its own (connection: vitrified clay; deposit: sediment).
double PipeFeatureDisplacementMm(const PipeFeature& f, double ds_mm, double dclock_rad,
                                 double radius_mm, std::uint64_t noise_seed,
                                 std::optional<Material>* own_material);

/// Cover (0 dry … 1) of a wet feature's film at a wall point `ds_mm` along the pipe from its
/// station and `dclock_rad` around from its clock: a rounded rectangle whose margin thins out
/// over 2 mm along an irregular line (`noise_seed`); 0 for the other kinds.
double PipeFeatureWetCover(const PipeFeature& f, double ds_mm, double dclock_rad, double radius_mm,
                           std::uint64_t noise_seed);

/// Width (mm) of the smoothed edges of the pipe world's features and joint gaps.
inline constexpr double kFeatureEdgeMm = 0.4;

/// A wet patch's ragged margin: its line wanders ±this (mm) about the rounded rectangle.
inline constexpr double kWetRaggedMm = 3.0;

/// 0 below −½, 1 above ½, smooth (cubic) in between: the edge profile of features.
inline double SmoothStep(double x) {
  const double u = std::clamp(x + 0.5, 0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);
}

/// Angle into [−π, π]: one subtraction for the small multiples of 2π met here, closed form
/// (std::remainder) for anything farther out.
inline double WrapAngle(double a) {
  if (a > std::numbers::pi) a -= kTwoPi;
  if (a < -std::numbers::pi) a += kTwoPi;
  if (a > std::numbers::pi || a < -std::numbers::pi) a = std::remainder(a, kTwoPi);
  return a;
}

/// `displacement_mm` plus the displacements of `features` at the wall point (station_mm,
/// clock_rad()) of a wall of nominal radius `radius_mm`. clock_rad() is called only when a
/// feature is near enough to need it (an atan2 the pipe world saves). With `material`, sets it
/// to the material where the wall rises most (a feature's own, or the one it had), if any
/// feature raises it.
template <typename ClockRad>
double AddPipeFeatures(double displacement_mm, std::span<const PipeFeature> features,
                       std::uint64_t material_seed, double radius_mm, double station_mm,
                       ClockRad&& clock_rad, Material* material) {
  const std::optional<Material> base = material ? std::optional<Material>(*material) : std::nullopt;
  std::optional<double> clock;
  double strongest = 0.0;
  for (std::size_t k = 0; k < features.size(); ++k) {
    const PipeFeature& f = features[k];
    const double ds = station_mm - f.station_mm;
    if (std::abs(ds) > PipeFeatureReachMm(f)) continue;
    if (!clock) clock = clock_rad();
    std::optional<Material> own;
    const double d = PipeFeatureDisplacementMm(
        f, ds, WrapAngle(*clock - ClockHoursToRad(f.clock_h)), radius_mm, material_seed + k, &own);
    displacement_mm += d;
    if (material && d > strongest) {
      strongest = d;
      *material = own.value_or(*base);
    }
  }
  return displacement_mm;
}

/// The water film's cover (0 dry … 1, the most of any wet feature's) at the wall point
/// (station_mm, clock_rad()) of a wall of nominal radius `radius_mm`; clock_rad() as for
/// AddPipeFeatures.
template <typename ClockRad>
double WetCover(std::span<const PipeFeature> features, std::uint64_t material_seed,
                double radius_mm, double station_mm, ClockRad&& clock_rad) {
  double cover = 0.0;
  for (std::size_t k = 0; k < features.size(); ++k) {
    const PipeFeature& f = features[k];
    const double ds = station_mm - f.station_mm;
    if (f.type != PipeFeature::Type::kWet || std::abs(ds) > PipeFeatureReachMm(f)) continue;
    const double dclock = WrapAngle(clock_rad() - ClockHoursToRad(f.clock_h));
    cover = std::max(cover, PipeFeatureWetCover(f, ds, dclock, radius_mm, material_seed + k));
  }
  return cover;
}

}  // namespace sewer3d
