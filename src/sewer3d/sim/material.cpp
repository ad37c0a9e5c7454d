#include "sewer3d/sim/material.hpp"

#include <algorithm>
#include <cmath>

#include "sewer3d/core/units.hpp"

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

// Fractal sum of octaves, result roughly in [0, 1].
double Fbm(std::uint64_t seed, double x, double y, int octaves) {
  double sum = 0.0, amplitude = 0.5, norm = 0.0;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * ValueNoise(seed + 1000 * o, x, y);
    norm += amplitude;
    x *= 2.03;
    y *= 2.03;
    amplitude *= 0.5;
  }
  return sum / norm;
}

// Aggregate grains: a jittered grid of irregular grains (cell 5 mm, radius 0.4–2.5 mm) a
// little brighter or darker than the cement around them.
double Aggregate(std::uint64_t seed, const Eigen::Vector2d& p) {
  constexpr double kCell = 5.0;
  const double cx = std::floor(p.x() / kCell), cy = std::floor(p.y() / kCell);
  double shade = 0.0;
  for (int dj = -1; dj <= 1; ++dj) {
    for (int di = -1; di <= 1; ++di) {
      const auto i = static_cast<std::uint64_t>(static_cast<std::int64_t>(cx) + di);
      const auto j = static_cast<std::uint64_t>(static_cast<std::int64_t>(cy) + dj);
      const Eigen::Vector2d centre((cx + di + HashUniform(seed, i, j, 1)) * kCell,
                                   (cy + dj + HashUniform(seed, i, j, 2)) * kCell);
      const double radius = 0.4 + 2.1 * HashUniform(seed, i, j, 3) * HashUniform(seed, i, j, 4);
      // Irregular outline: the radius wobbles with the direction.
      const Eigen::Vector2d d = p - centre;
      if (d.squaredNorm() > 1.5625 * radius * radius) continue;  // beyond the largest wobble
      const double wobble =
          0.75 + 0.5 * ValueNoise(seed + i * 31 + j, 2.0 + std::atan2(d.y(), d.x()), 0.5);
      const double r = d.norm() / (radius * wobble);
      if (r < 1.0) {
        const double edge = std::min(1.0, (1.0 - r) * radius * 3.0);
        shade = (HashUniform(seed, i, j, 5) - 0.5) * 0.16 * edge;
      }
    }
  }
  return shade;
}

}  // namespace

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
    case Material::kConcrete: {
      const double mottling = Fbm(seed, p.x() / 3.0, p.y() / 3.0, 4) - 0.5;  // 3 mm and finer
      const double stain = std::max(0.0, Fbm(seed + 7, p.x() / 60.0, p.y() / 60.0, 2) - 0.55);
      const double grey = 0.45 + 0.22 * mottling + Aggregate(seed + 13, p);
      const Eigen::Vector3d base(grey, grey * 0.98, grey * 0.94);
      const Eigen::Vector3d stained = base.cwiseProduct(Eigen::Vector3d(0.75, 0.65, 0.5));
      const double w = std::min(1.0, stain * 4.0);
      return ((1 - w) * base + w * stained).cwiseMax(0.02).cwiseMin(0.95);
    }
    case Material::kVitrifiedClay: {
      const double streak = Fbm(seed, p.x() / 40.0, p.y() / 4.0, 3) - 0.5;
      const double speck = Fbm(seed + 3, p.x() / 1.5, p.y() / 1.5, 2) - 0.5;
      const double k = 1.0 + 0.25 * streak + 0.1 * speck;
      return (Eigen::Vector3d(0.36, 0.20, 0.12) * k).cwiseMax(0.02).cwiseMin(0.95);
    }
    case Material::kPlastic: {
      const double k = 1.0 + 0.02 * (Fbm(seed, p.x() / 50.0, p.y() / 50.0, 2) - 0.5);
      return Eigen::Vector3d(0.62, 0.50, 0.40) * k;
    }
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
