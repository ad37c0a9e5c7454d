#pragma once
/// \file
/// Angle units. Lengths are millimetres throughout and need no conversion.

#include <numbers>

namespace sewer3d {

inline constexpr double kRadPerDeg = std::numbers::pi / 180.0;
inline constexpr double kDegPerRad = 180.0 / std::numbers::pi;

}  // namespace sewer3d
