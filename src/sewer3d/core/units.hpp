#pragma once
/// \file
/// Angle units. Lengths are millimetres throughout and need no conversion.

#include <cmath>
#include <numbers>

namespace sewer3d {

/// One full turn in radians.
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;
/// Radians per degree: angle_rad = angle_deg * kRadPerDeg.
inline constexpr double kRadPerDeg = std::numbers::pi / 180.0;

/// Degrees to radians.
constexpr double DegToRad(double angle_deg) { return angle_deg * kRadPerDeg; }
/// Degrees per radian: angle_deg = angle_rad * kDegPerRad.
inline constexpr double kDegPerRad = 180.0 / std::numbers::pi;

/// Radians to degrees.
constexpr double RadToDeg(double angle_rad) { return angle_rad / kRadPerDeg; }
/// A clock position (hours, 12 = one turn, as in EN 13508-2) to radians.
constexpr double ClockHoursToRad(double clock_h) { return clock_h * std::numbers::pi / 6.0; }
/// Radians (0 = crown, any number of turns) to a clock position in (0, 12] hours: 12 at the
/// crown, as EN 13508-2 writes it.
inline double ClockRadToHours(double clock_rad) {
  const double h = std::fmod(clock_rad * 6.0 / std::numbers::pi, 12.0);
  const double wrapped = h < 0.0 ? h + 12.0 : h;
  return wrapped < 1e-9 ? 12.0 : wrapped;
}

}  // namespace sewer3d
