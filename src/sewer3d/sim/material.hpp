#pragma once
/// \file
/// Procedural albedo of sewer materials, in linear RGB [0, 1], as a function of 2-D surface
/// coordinates (mm). Deterministic for a seed.

#include <Eigen/Core>
#include <cstdint>

namespace sewer3d {

/// Values are stable (files and figures index by them): new materials go at the end.
enum class Material { kConcrete, kVitrifiedClay, kPlastic, kSediment, kPolyethylene };

/// Plastic pipe (PVC, PP, PE): smooth to micrometres and translucent, whatever its colour
/// (spot_errors: relief_plastic_mm, subsurface_plastic_mm).
constexpr bool IsPlastic(Material m) {
  return m == Material::kPlastic || m == Material::kPolyethylene;
}

/// Albedo at surface coordinates `p_mm` (x round the pipe, y along it), detailed down to the
/// ~0.1 mm per pixel of the texture images (docs/simulator.md, "Materials"):
/// - concrete: grey cement (~0.47) mottled at 2–10 mm with sand speckle at 0.15–0.4 mm; angular
///   aggregate (Voronoi polygons of 2.2 and 7 mm cells with crisp edges; light, mid-grey and
///   dark rock); pores 0.2–1.8 mm across (dark pits); faint formwork lines along the pipe;
///   large brownish stains. Mean ~0.45;
/// - vitrified clay: glazed reddish brown (~0.36, 0.2, 0.12) with streaks, glaze crazing (a
///   network of dark hairline cracks round 3.5 mm and fainter 1.3 mm cells), dark and light
///   specks 0.1–0.7 mm;
/// - plastic: orange-grey (0.62, 0.5, 0.4), 2 % low-frequency variation, extrusion lines along
///   the pipe (< 1 %), sparse light scratches; nearly featureless;
/// - sediment: dark brown grit with patches (deposits at the invert);
/// - polyethylene: the plastic's structure in carbon black (~0.045, 0.045, 0.05): black PE-HD
///   pipe, the decoder's faint-spot case (docs/decoder.md, "Hard surfaces").
/// Pure function: the same (material, seed, point) always gives the same albedo.
Eigen::Vector3d MaterialAlbedo(Material material, std::uint64_t seed, const Eigen::Vector2d& p_mm);

/// Smooth fractal value noise in [0, 1] with a unit feature size at the first octave.
double SmoothNoise(std::uint64_t seed, double x, double y, int octaves);

/// Standard normal variate from hashed uniforms (Box–Muller), deterministic for (a, b, c).
double HashNormal(std::uint64_t a, std::uint64_t b, std::uint64_t c);

/// Deterministic hash of integers to a uniform double in [0, 1).
double HashUniform(std::uint64_t a, std::uint64_t b = 0, std::uint64_t c = 0, std::uint64_t d = 0);

}  // namespace sewer3d
