#pragma once
/// \file
/// Angle units used across sewer3d: degrees and radians, and clock positions in hours as in
/// EN 13508-2 (12 h = one turn). One definition, so that every module converts alike and the
/// results agree to the bit.

#include <numbers>

namespace sewer3d {

/// One full turn in radians.
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;
/// Radians per degree: angle_rad = angle_deg * kRadPerDeg.
inline constexpr double kRadPerDeg = std::numbers::pi / 180.0;

/// Degrees to radians.
constexpr double DegToRad(double angle_deg) { return angle_deg * kRadPerDeg; }
/// Radians to degrees.
constexpr double RadToDeg(double angle_rad) { return angle_rad / kRadPerDeg; }
/// A clock position (hours, 12 = one turn, as in EN 13508-2) to radians.
constexpr double ClockHoursToRad(double clock_h) { return clock_h * std::numbers::pi / 6.0; }

}  // namespace sewer3d
