#pragma once
/// \file
/// Internal to sim/: the albedo of each wall material (MaterialAlbedo dispatches here), linear
/// RGB, surface coordinates in mm on the unrolled wall (x round the pipe, y along it).

#include <Eigen/Core>
#include <cstdint>

namespace sewer3d {

/// Concrete: cement paste with mottling, sand speckle, angular aggregate, pores, formwork marks
/// and stains (material_concrete.cpp).
Eigen::Vector3d ConcreteAlbedo(std::uint64_t seed, const Eigen::Vector2d& p_mm);
/// Vitrified clay: reddish-brown glaze with streaks, a crazing network and specks
/// (material_clay.cpp).
Eigen::Vector3d ClayAlbedo(std::uint64_t seed, const Eigen::Vector2d& p_mm);
/// Plastic: orange-grey with faint extrusion lines along the pipe and sparse scratches
/// (material.cpp).
Eigen::Vector3d PlasticAlbedo(std::uint64_t seed, const Eigen::Vector2d& p_mm);

/// Black polyethylene: the plastic's structure in carbon black.
Eigen::Vector3d PolyethyleneAlbedo(std::uint64_t seed, const Eigen::Vector2d& p_mm);

}  // namespace sewer3d
