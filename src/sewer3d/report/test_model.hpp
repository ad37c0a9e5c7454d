#pragma once
/// \file
/// For the report's tests only: a small straight pipe model with a known feature — a red disc
/// on a flat-topped outward bump — on a grey texture with station rings and hour lines.

#include <algorithm>
#include <cmath>
#include <limits>

#include "sewer3d/inspect/observation.hpp"
#include "sewer3d/inspect/profile.hpp"
#include "sewer3d/model/pipe_map.hpp"

namespace sewer3d::testing_report {

struct KnownBump {
  double station_mm = 120.0;
  double clock_h = 9.0;  // facing the viewer's first view
  double height_mm = 3.0;
  double plateau_radius_mm = 9.0;  ///< full height inside, falling to 0 at +5 mm
  double disc_radius_mm = 6.0;     ///< red inside
};

inline Centreline StraightCentreline(double begin_mm, double end_mm, double radius_mm) {
  Centreline c;
  c.station0_mm = begin_mm - 20.0;
  c.step_mm = 10.0;
  c.radius_mm = radius_mm;
  for (double s = c.station0_mm; s <= end_mm + 20.0 + 1e-9; s += c.step_mm) {
    c.points.emplace_back(0.0, 0.0, s);
    c.crowns.emplace_back(0.0, -1.0, 0.0);
  }
  return c;
}

/// Distance on the wall (mm) from the bump's centre to cell (row, col) of `grid`.
inline double WallDistanceMm(const MapGrid& grid, int row, int col, double radius_mm,
                             const KnownBump& bump) {
  const double ds = grid.RowStationMm(row) - bump.station_mm;
  double dt = grid.ColClockRad(col) - bump.clock_h / 12.0 * 2.0 * M_PI;
  dt = std::remainder(dt, 2.0 * M_PI);
  return std::hypot(ds, dt * radius_mm);
}

/// Maps over `grid` with the bump; an uncovered 6 mm × 0.5 h hole at station 40 mm, 6 h.
inline PipeMaps BumpMaps(const MapGrid& grid, double radius_mm, const KnownBump& bump) {
  PipeMaps m;
  m.grid = grid;
  m.texture = cv::Mat3b(grid.rows, grid.cols, cv::Vec3b(150, 165, 172));
  m.displacement_mm = cv::Mat1f(grid.rows, grid.cols, 0.0F);
  m.samples = cv::Mat1w(grid.rows, grid.cols, 4);
  m.coverage = cv::Mat1b(grid.rows, grid.cols, static_cast<std::uint8_t>(Coverage::kMeasured));
  for (int r = 0; r < grid.rows; ++r) {
    const double s = grid.RowStationMm(r);
    for (int c = 0; c < grid.cols; ++c) {
      const double hours = grid.ColClockRad(c) / (2.0 * M_PI) * 12.0;
      if (std::fmod(s + 1000.0, 20.0) < 2.0 || std::abs(hours - std::round(hours)) < 0.02)
        m.texture(r, c) = cv::Vec3b(90, 100, 105);
      const double d = WallDistanceMm(grid, r, c, radius_mm, bump);
      const double fall = std::clamp((d - bump.plateau_radius_mm) / 5.0, 0.0, 1.0);
      m.displacement_mm(r, c) =
          static_cast<float>(bump.height_mm * 0.5 * (1 + std::cos(M_PI * fall)));
      if (d < bump.disc_radius_mm) m.texture(r, c) = cv::Vec3b(30, 30, 220);
      if (std::abs(s - 40.0) < 3.0 && std::abs(hours - 6.0) < 0.25) {
        m.texture(r, c) = cv::Vec3b(0, 0, 0);
        m.displacement_mm(r, c) = std::numeric_limits<float>::quiet_NaN();
        m.samples(r, c) = 0;
        m.coverage(r, c) = static_cast<std::uint8_t>(Coverage::kNone);
      }
    }
  }
  return m;
}

/// An observation at the bump with its crop (±20 mm, ±0.5 h).
inline Observation BumpObservation(const MapGrid& grid, const KnownBump& bump) {
  Observation o;
  o.id = "O1";
  o.code = "BAF";
  o.station_mm = bump.station_mm;
  o.clock_h = o.clock_from_h = o.clock_to_h = bump.clock_h;
  o.confidence = 0.9;
  o.quantities = {{"depth_max_mm", -bump.height_mm, "mm"}, {"area_mm2", 250.0, "mm2"}};
  o.remark = "test bump";
  const int row = static_cast<int>((bump.station_mm - grid.station0_mm) / grid.resolution_mm);
  const int col = static_cast<int>(bump.clock_h / 12.0 * grid.cols);
  o.crop = {row - static_cast<int>(20 / grid.resolution_mm),
            static_cast<int>(40 / grid.resolution_mm), col - grid.cols / 24, grid.cols / 12};
  return o;
}

/// A profile of a slightly oval pipe, one row every 10 mm, one row not measured (NaN).
inline Profile OvalProfile(double begin_mm, double end_mm, double radius_mm) {
  Profile p;
  p.nominal_diameter_mm = 2.0 * radius_mm;
  for (double s = begin_mm; s <= end_mm; s += 10.0) {
    ProfileRow r;
    r.station_mm = s;
    r.coverage = 1.0;
    r.mean_diameter_mm = 2.0 * radius_mm + 0.5 * std::sin(s / 50.0);
    r.min_diameter_mm = r.mean_diameter_mm - 1.0;
    r.max_diameter_mm = r.mean_diameter_mm + 1.0;
    r.ovality_en_pct = 100.0 / r.mean_diameter_mm;
    r.ovality_astm_pct = 100.0 / r.mean_diameter_mm;
    p.rows.push_back(r);
  }
  if (p.rows.size() > 3) p.rows[2].mean_diameter_mm = std::numeric_limits<double>::quiet_NaN();
  return p;
}

}  // namespace sewer3d::testing_report
