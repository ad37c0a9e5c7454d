#include "sewer3d/sim/material.hpp"

#include <algorithm>
#include <cmath>

#include "sewer3d/core/units.hpp"
#include "sewer3d/sim/material_noise.hpp"
#include "sewer3d/sim/material_walls.hpp"

namespace sewer3d {
namespace {

std::uint64_t Mix(std::uint64_t x) {  // splitmix64 finaliser
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

double Lattice(std::uint64_t seed, std::int64_t i, std::int64_t j) {
  return HashUniform(seed, static_cast<std::uint64_t>(i), static_cast<std::uint64_t>(j));
}

// Smooth value noise in [0, 1] with unit lattice spacing.
double ValueNoise(std::uint64_t seed, double x, double y) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto i = static_cast<std::int64_t>(fx), j = static_cast<std::int64_t>(fy);
  double u = x - fx, v = y - fy;
  u = u * u * (3 - 2 * u);
  v = v * v * (3 - 2 * v);
  const double a = Lattice(seed, i, j), b = Lattice(seed, i + 1, j);
  const double c = Lattice(seed, i, j + 1), d = Lattice(seed, i + 1, j + 1);
  return (a * (1 - u) + b * u) * (1 - v) + (c * (1 - u) + d * u) * v;
}

// Fractal sum of this file's value noise (the geometry's SmoothNoise keeps its values).
double Fbm(std::uint64_t seed, double x, double y, int octaves) {
  return material_noise::FractalSum(ValueNoise, seed, x, y, octaves);
}

// Extruded pipe of a base colour: faint ridges along the pipe, low-frequency variation, sparse
// light scratches.
Eigen::Vector3d ExtrudedAlbedo(std::uint64_t seed, const Eigen::Vector2d& p,
                               const Eigen::Vector3d& base) {
  namespace mn = material_noise;
  // Extrusion lines: the die leaves faint ridges along the pipe (constant round it), ~1 mm apart.
  const double x = p.x() + 0.5 * mn::ValueNoise(seed + 3, p.y() / 200.0, 0.5);
  const double lines = mn::ValueNoise(seed + 5, x / 1.2, 0.5) - 0.5 +
                       0.5 * (mn::ValueNoise(seed + 6, x / 0.5, 0.5) - 0.5);
  double k = 1.0 + 0.02 * (Fbm(seed, p.x() / 50.0, p.y() / 50.0, 2) - 0.5) + 0.008 * lines;
  // Sparse scratches: in a quarter of the 30 mm cells a straight segment 4–20 mm long, 0.12 mm
  // wide, lighter (stress whitening).
  constexpr double kCell = 30.0;
  const double fx = std::floor(p.x() / kCell), fy = std::floor(p.y() / kCell);
  const std::uint64_t h =
      mn::CellHash(seed + 9, static_cast<std::int64_t>(fx), static_cast<std::int64_t>(fy));
  if (mn::Unit(h, 0) < 0.25) {
    const double half = 2.0 + 8.0 * mn::Unit(h, 1);
    const double angle = kTwoPi * mn::Unit(h, 2);
    const Eigen::Vector2d along(std::cos(angle), std::sin(angle));
    const Eigen::Vector2d centre =
        kCell * Eigen::Vector2d(fx + 0.5, fy + 0.5) + (kCell / 3) * (mn::Unit(h, 3) - 0.5) * along;
    const Eigen::Vector2d d = p - centre;
    const double t = std::clamp(d.dot(along), -half, half);
    k *= 1.0 + 0.05 * mn::Band((d - t * along).norm(), 0.06, 0.05);
  }
  return base * k;
}

}  // namespace

Eigen::Vector3d PlasticAlbedo(std::uint64_t seed, const Eigen::Vector2d& p) {
  return ExtrudedAlbedo(seed, p, {0.62, 0.50, 0.40});
}

Eigen::Vector3d PolyethyleneAlbedo(std::uint64_t seed, const Eigen::Vector2d& p) {
  return ExtrudedAlbedo(seed, p, {0.045, 0.045, 0.05});
}

double SmoothNoise(std::uint64_t seed, double x, double y, int octaves) {
  return Fbm(seed, x, y, octaves);
}

double HashNormal(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  const double u1 = std::max(HashUniform(a, b, c, 11), 1e-300);
  const double u2 = HashUniform(a, b, c, 12);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
}

double HashUniform(std::uint64_t a, std::uint64_t b, std::uint64_t c, std::uint64_t d) {
  const std::uint64_t h = Mix(a ^ Mix(b ^ Mix(c ^ Mix(d))));
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

Eigen::Vector3d MaterialAlbedo(Material material, std::uint64_t seed, const Eigen::Vector2d& p) {
  switch (material) {
    case Material::kConcrete:
      return ConcreteAlbedo(seed, p);
    case Material::kVitrifiedClay:
      return ClayAlbedo(seed, p);
    case Material::kPlastic:
      return PlasticAlbedo(seed, p);
    case Material::kPolyethylene:
      return PolyethyleneAlbedo(seed, p);
    case Material::kSediment: {
      const double grit = Fbm(seed + 5, p.x() / 2.0, p.y() / 2.0, 3) - 0.5;
      const double patch = Fbm(seed + 9, p.x() / 25.0, p.y() / 25.0, 2) - 0.5;
      const double k = 1.0 + 0.35 * grit + 0.3 * patch;
      return (Eigen::Vector3d(0.30, 0.25, 0.17) * k).cwiseMax(0.02).cwiseMin(0.95);
    }
  }
  return Eigen::Vector3d::Constant(0.5);
}

}  // namespace sewer3d
