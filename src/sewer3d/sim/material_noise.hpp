#pragma once
/// \file
/// Internal to sim/: the cheap hashed noise the procedural materials are built from. Every
/// function is a pure function of its arguments (deterministic for a seed, thread-safe). A
/// full-size frame asks for 45 M albedos, so these inline and hash with two splitmix rounds.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace sewer3d::material_noise {

inline std::uint64_t Mix(std::uint64_t x) {  // splitmix64 finaliser
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// 64 random bits for the lattice cell (i, j) of a layer's seed.
inline std::uint64_t CellHash(std::uint64_t seed, std::int64_t i, std::int64_t j) {
  return Mix(seed ^ Mix(static_cast<std::uint64_t>(i) * 0x9e3779b97f4a7c15ULL ^
                        static_cast<std::uint64_t>(j) * 0xc2b2ae3d27d4eb4fULL));
}

/// The k-th of four 16-bit uniforms in [0, 1) packed in a hash.
inline double Unit(std::uint64_t h, int k) {
  return static_cast<double>((h >> (16 * k)) & 0xffffU) * (1.0 / 65536.0);
}

/// Smooth value noise in [0, 1], unit lattice spacing.
inline double ValueNoise(std::uint64_t seed, double x, double y) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto i = static_cast<std::int64_t>(fx), j = static_cast<std::int64_t>(fy);
  double u = x - fx, v = y - fy;
  u = u * u * (3 - 2 * u);
  v = v * v * (3 - 2 * v);
  const double a = Unit(CellHash(seed, i, j), 0), b = Unit(CellHash(seed, i + 1, j), 0);
  const double c = Unit(CellHash(seed, i, j + 1), 0), d = Unit(CellHash(seed, i + 1, j + 1), 0);
  return (a * (1 - u) + b * u) * (1 - v) + (c * (1 - u) + d * u) * v;
}

/// Fractal sum of `octaves` octaves of `noise(seed, x, y)` ∈ [0, 1] (lacunarity 2.03, gain
/// 0.5, each octave its own seed), roughly in [0, 1].
template <typename Noise>
double FractalSum(Noise noise, std::uint64_t seed, double x, double y, int octaves) {
  double sum = 0.0, amplitude = 0.5, norm = 0.0;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * noise(seed + 1000 * o, x, y);
    norm += amplitude;
    x *= 2.03;
    y *= 2.03;
    amplitude *= 0.5;
  }
  return sum / norm;
}

/// FractalSum of ValueNoise.
inline double Fbm(std::uint64_t seed, double x, double y, int octaves) {
  return FractalSum(ValueNoise, seed, x, y, octaves);
}

/// The Voronoi cell of a jittered grid (one site per unit cell) that contains a point.
struct VoronoiCell {
  std::uint64_t hash = 0;   ///< the site's cell hash: its random properties
  double edge = 0.0;        ///< distance to the cell's nearest edge (bisector), lattice units
  Eigen::Vector2d to_site;  ///< site − point
};

/// Nearest site among the 3 × 3 neighbouring cells, and the exact distance to the cell's
/// boundary: min over the other sites b of (|b − p|² − |a − p|²) / (2 |b − a|). The cells are
/// convex polygons, which gives angular grains and crack networks with straight edges.
inline VoronoiCell Voronoi(std::uint64_t seed, double x, double y) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto i0 = static_cast<std::int64_t>(fx), j0 = static_cast<std::int64_t>(fy);
  Eigen::Vector2d sites[9];
  std::uint64_t hashes[9];
  int best = 0;
  double best_d2 = 1e300;
  for (int k = 0; k < 9; ++k) {
    const int di = k % 3 - 1, dj = k / 3 - 1;
    hashes[k] = CellHash(seed, i0 + di, j0 + dj);
    // Sites kept 10 % away from the cell border so that no cell degenerates to a sliver.
    sites[k] = Eigen::Vector2d(fx + di + 0.1 + 0.8 * Unit(hashes[k], 0) - x,
                               fy + dj + 0.1 + 0.8 * Unit(hashes[k], 1) - y);
    const double d2 = sites[k].squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best = k;
  }
  double edge = 1e300;
  for (int k = 0; k < 9; ++k) {
    if (k == best) continue;
    const double gap = (sites[k] - sites[best]).norm();
    edge = std::min(edge, (sites[k].squaredNorm() - best_d2) / (2.0 * gap));
  }
  return {hashes[best], edge, sites[best]};
}

/// 1 inside the band |d| < half_width, 0 outside, with a linear edge `soft` wide.
inline double Band(double d, double half_width, double soft) {
  return std::clamp((half_width - std::abs(d)) / soft + 0.5, 0.0, 1.0);
}

}  // namespace sewer3d::material_noise
