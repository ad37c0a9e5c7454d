#pragma once
/// \file
/// Procedural albedo of sewer materials, in linear RGB [0, 1], as a function of 2-D surface
/// coordinates (mm). Deterministic for a seed.

#include <Eigen/Core>
#include <cstdint>

namespace sewer3d {

enum class Material { kConcrete, kVitrifiedClay, kPlastic, kSediment };

/// Albedo at surface coordinates `p_mm`:
/// - concrete: grey cement (~0.45) with multi-scale mottling, aggregate grains 1–8 mm of
///   varying brightness, and large brownish stains;
/// - vitrified clay: glazed reddish brown (~0.35, 0.2, 0.12) with faint streaks;
/// - plastic: nearly uniform light orange-grey with 1 % low-frequency variation;
/// - sediment: dark brown grit with patches (deposits at the invert).
Eigen::Vector3d MaterialAlbedo(Material material, std::uint64_t seed, const Eigen::Vector2d& p_mm);

/// Smooth fractal value noise in [0, 1] with a unit feature size at the first octave.
double SmoothNoise(std::uint64_t seed, double x, double y, int octaves);

/// Standard normal variate from hashed uniforms (Box–Muller), deterministic for (a, b, c).
double HashNormal(std::uint64_t a, std::uint64_t b, std::uint64_t c);

/// Deterministic hash of integers to a uniform double in [0, 1).
double HashUniform(std::uint64_t a, std::uint64_t b = 0, std::uint64_t c = 0, std::uint64_t d = 0);

}  // namespace sewer3d
