// Vitrified clay at the scale of the texture images (~0.1 mm per pixel): a salt or slip glaze,
// reddish brown, crazed by the glaze's shrinkage into a network of hairline cracks a few mm
// across, with dark iron/manganese specks and light grog grains showing through.
#include <algorithm>
#include <cmath>

#include "sewer3d/sim/material_noise.hpp"
#include "sewer3d/sim/material_walls.hpp"

namespace sewer3d {
namespace {

using namespace material_noise;  // NOLINT(google-build-using-namespace): internal helpers

// Hairline cracks along the edges of warped Voronoi cells `cell_mm` across, `width_mm` wide;
// each cell's cracks have their own darkness (some are stained, some barely open). Returns the
// fraction of light the cracks take away.
double Crazing(std::uint64_t seed, const Eigen::Vector2d& p, double cell_mm, double width_mm,
               double darkness) {
  // A gentle warp bends the straight Voronoi edges into the wavy lines of real crazing.
  const double wx = 0.12 * cell_mm * (ValueNoise(seed + 1, p.x() / 1.7, p.y() / 1.7) - 0.5);
  const double wy = 0.12 * cell_mm * (ValueNoise(seed + 2, p.x() / 1.7, p.y() / 1.7) - 0.5);
  const VoronoiCell c = Voronoi(seed, (p.x() + wx) / cell_mm, (p.y() + wy) / cell_mm);
  const double d = c.edge * cell_mm;
  if (d > width_mm) return 0.0;
  return darkness * (0.5 + 0.5 * Unit(Mix(c.hash), 0)) * Band(d, 0.5 * width_mm, 0.04);
}

// Specks in a 1.6 mm grid: dark (r 0.05–0.35 mm) in 35 % of the cells, light in 12 %.
Eigen::Vector3d SpeckFactor(std::uint64_t seed, const Eigen::Vector2d& p) {
  constexpr double kCell = 1.6;
  const double fx = std::floor(p.x() / kCell), fy = std::floor(p.y() / kCell);
  const std::uint64_t h =
      CellHash(seed, static_cast<std::int64_t>(fx), static_cast<std::int64_t>(fy));
  const double kind = Unit(h, 0);
  if (kind >= 0.47) return Eigen::Vector3d::Ones();
  const double r = 0.05 + 0.3 * Unit(h, 1) * Unit(h, 1);
  const Eigen::Vector2d centre(fx * kCell + r + (kCell - 2 * r) * Unit(h, 2),
                               fy * kCell + r + (kCell - 2 * r) * Unit(h, 3));
  const double d = (p - centre).norm();
  if (d >= r + 0.03) return Eigen::Vector3d::Ones();
  const double w = Band(d, r, 0.06);
  const Eigen::Vector3d speck =
      kind < 0.35 ? Eigen::Vector3d(0.35, 0.33, 0.38) : Eigen::Vector3d(1.7, 1.8, 1.9);
  return (1 - w) * Eigen::Vector3d::Ones() + w * speck;
}

}  // namespace

Eigen::Vector3d ClayAlbedo(std::uint64_t seed, const Eigen::Vector2d& p) {
  const double streak = Fbm(seed, p.x() / 40.0, p.y() / 4.0, 3) - 0.5;
  const double mottle = Fbm(seed + 3, p.x() / 3.0, p.y() / 3.0, 2) - 0.5;
  const double grain = ValueNoise(seed + 4, p.x() / 0.3, p.y() / 0.3) - 0.5;
  const double k = (1.0 + 0.25 * streak + 0.12 * mottle + 0.08 * grain) *
                   (1.0 - Crazing(seed + 31, p, 3.5, 0.14, 0.6)) *
                   (1.0 - Crazing(seed + 37, p, 1.3, 0.08, 0.3));
  const Eigen::Vector3d albedo =
      Eigen::Vector3d(0.36, 0.20, 0.12).cwiseProduct(SpeckFactor(seed + 41, p)) * k;
  return albedo.cwiseMax(0.02).cwiseMin(0.95);
}

}  // namespace sewer3d
