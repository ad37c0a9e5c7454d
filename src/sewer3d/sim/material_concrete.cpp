// Concrete at the scale of the texture images (~0.1 mm per pixel). Sizes follow what a
// sewer-pipe concrete shows on its wetted, slightly abraded surface: crushed aggregate up to
// 8–16 mm whose angular sections are exposed at the surface, sand grains of 0.1–1 mm in the
// paste, air voids of 0.2–2 mm, and faint lines left by the mould's joints.
#include <algorithm>
#include <cmath>

#include "sewer3d/sim/material_noise.hpp"
#include "sewer3d/sim/material_walls.hpp"

namespace sewer3d {
namespace {

using namespace material_noise;  // NOLINT(google-build-using-namespace): internal helpers

struct Grain {
  bool hit = false;
  double grey = 0.0;
  Eigen::Vector3d tint = Eigen::Vector3d::Ones();
};

// Aggregate of one size class: Voronoi cells `cell_mm` across; a cell holds a grain with
// probability `fill`, shrunk from the cell's edges by a cement band `band_mm` wide, so the
// grain is a convex polygon with straight, crisp edges. Rock types: light (limestone,
// quartz), mid grey, dark (basalt).
Grain Aggregate(std::uint64_t seed, const Eigen::Vector2d& p, double cell_mm, double fill,
                double band_mm) {
  const VoronoiCell c = Voronoi(seed, p.x() / cell_mm, p.y() / cell_mm);
  const std::uint64_t h = Mix(c.hash);
  if (Unit(h, 0) >= fill) return {};
  const double band = band_mm * (0.4 + 1.2 * Unit(h, 1));
  if (c.edge * cell_mm < band) return {};
  Grain g;
  g.hit = true;
  const double type = Unit(h, 2), tone = Unit(h, 3);
  if (type < 0.35) {
    g.grey = 0.58 + 0.12 * tone;
    g.tint = {1.0, 0.97, 0.91};
  } else if (type < 0.7) {
    g.grey = 0.38 + 0.12 * tone;
  } else {
    g.grey = 0.18 + 0.10 * tone;
    g.tint = {0.96, 1.0, 1.04};
  }
  // Shading across the grain: its exposed face is not quite flat nor uniform.
  g.grey *= 1.0 + 0.08 * c.to_site.x() * (Unit(h, 1) - 0.5);
  return g;
}

// An air void: a dark pit 0.2–1.8 mm across (small ones far more common), at most one per
// 2.5 mm cell, darkest at its centre where the ring light does not reach.
double PoreFactor(std::uint64_t seed, const Eigen::Vector2d& p) {
  constexpr double kCell = 2.5;
  const double fx = std::floor(p.x() / kCell), fy = std::floor(p.y() / kCell);
  const std::uint64_t h =
      CellHash(seed, static_cast<std::int64_t>(fx), static_cast<std::int64_t>(fy));
  if (Unit(h, 0) >= 0.45) return 1.0;
  const double u = Unit(h, 1);
  const double r = 0.1 + 0.8 * u * u * u;
  const Eigen::Vector2d centre(fx * kCell + r + (kCell - 2 * r) * Unit(h, 2),
                               fy * kCell + r + (kCell - 2 * r) * Unit(h, 3));
  const double d2 = (p - centre).squaredNorm();
  if (d2 >= r * r) return 1.0;
  return 0.22 + 0.35 * d2 / (r * r);
}

// Faint lines along the pipe where the mould's panels met: at most one per 60 mm of
// circumference, 0.6 mm wide, wandering a little and fading in and out along their length.
double FormworkFactor(std::uint64_t seed, const Eigen::Vector2d& p) {
  constexpr double kCell = 60.0;
  const double fx = std::floor(p.x() / kCell);
  const std::uint64_t h = CellHash(seed, static_cast<std::int64_t>(fx), 0);
  if (Unit(h, 0) >= 0.6) return 1.0;
  const double wander = 2.0 * (ValueNoise(seed + 1, p.y() / 150.0, fx) - 0.5);
  const double x = fx * kCell + 5.0 + (kCell - 10.0) * Unit(h, 1) + wander;
  if (std::abs(p.x() - x) > 0.6) return 1.0;
  const double fade = ValueNoise(seed + 2, p.y() / 40.0, fx);
  return 1.0 - 0.07 * fade * Band(p.x() - x, 0.3, 0.15);
}

}  // namespace

Eigen::Vector3d ConcreteAlbedo(std::uint64_t seed, const Eigen::Vector2d& p) {
  // Cement paste: grey, mottled at 2–10 mm, with sand speckle at 0.15–0.4 mm.
  const double mottling = Fbm(seed, p.x() / 6.0, p.y() / 6.0, 3) - 0.5;
  const double sand = ValueNoise(seed + 21, p.x() / 0.35, p.y() / 0.35) - 0.5 +
                      0.6 * (ValueNoise(seed + 22, p.x() / 0.16, p.y() / 0.16) - 0.5);
  double grey = 0.47 + 0.14 * mottling + 0.16 * sand;
  Eigen::Vector3d tint(1.0, 0.98, 0.94);
  Grain grain = Aggregate(seed + 13, p, 7.0, 0.55, 0.45);
  if (!grain.hit) grain = Aggregate(seed + 17, p, 2.2, 0.4, 0.2);
  if (grain.hit) {
    grey = grain.grey * (1.0 + 0.25 * sand);
    tint = grain.tint;
  } else {
    grey *= PoreFactor(seed + 19, p);
  }
  grey *= FormworkFactor(seed + 23, p);
  const Eigen::Vector3d base = grey * tint;
  // Large brownish stains (iron, biofilm) that tint everything beneath them.
  const double stain = std::max(0.0, Fbm(seed + 7, p.x() / 60.0, p.y() / 60.0, 2) - 0.55);
  const double w = std::min(1.0, stain * 4.0);
  const Eigen::Vector3d stained = base.cwiseProduct(Eigen::Vector3d(0.75, 0.65, 0.5));
  return ((1 - w) * base + w * stained).cwiseMax(0.02).cwiseMin(0.95);
}

}  // namespace sewer3d
