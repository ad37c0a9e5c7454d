#pragma once
/// \file
/// The pipe model's data (paper §4.4, DESIGN.md "processing workspace"): a centreline with its
/// moving frame, the regular (station, clock) grid, and the maps over it. Conventions:
/// - model frame: origin at the carrier centre at the run's first image, z along the pipe,
///   y down, x right (as the carrier was then);
/// - row r = station (mm along the centreline), column c = clock angle, 0 at the crown,
///   increasing clockwise looking downstream (toward 3 o'clock = +x when the centreline runs
///   along +z); cell centres at (r + ½, c + ½) × cell size;
/// - a map point is centreline(station) + (radius + displacement) · direction(clock).

#include <Eigen/Core>
#include <cstddef>
#include <opencv2/core/mat.hpp>
#include <vector>

namespace sewer3d {

/// The centreline's moving frame at one station: `origin` on the axis, unit `tangent` along
/// the pipe (downstream), unit `crown` (clock 12) perpendicular to it, and `right` (clock 3)
/// = tangent × crown.
struct AxisFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d tangent = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d crown = -Eigen::Vector3d::UnitY();
  Eigen::Vector3d right = Eigen::Vector3d::UnitX();

  /// Unit direction from the axis toward the wall at clock angle `clock_rad` (0 = crown,
  /// π/2 = 3 o'clock): cos · crown + sin · right.
  [[nodiscard]] Eigen::Vector3d Direction(double clock_rad) const;
};

/// Axis points sampled every `step_mm` of station from `station0_mm`, each with its crown
/// direction (unit, perpendicular to the local tangent). Station = arc length along the axis;
/// station 0 is where the axis passes the model frame's origin (plus the user's start station).
struct Centreline {
  double station0_mm = 0.0;
  double step_mm = 10.0;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3d> crowns;
  double radius_mm = 150.0;  ///< the model radius: the nominal round pipe

  [[nodiscard]] double EndStationMm() const;
  /// The unit tangent at sample `i` (central difference, one-sided at the ends).
  [[nodiscard]] Eigen::Vector3d TangentAt(std::size_t i) const;
  /// The frame at `station_mm`: origin interpolated linearly between samples, tangent
  /// interpolated between the samples' tangents (so the frame turns continuously and a point
  /// has one station, see unroll.hpp); beyond the ends the axis goes on straight along the
  /// end tangent.
  [[nodiscard]] AxisFrame FrameAt(double station_mm) const;
};

/// The regular map grid: `rows` stations from `station0_mm` (edge of row 0) every
/// `resolution_mm`, `cols` clock angles over the full turn (cols = round(2π r / resolution)).
struct MapGrid {
  double resolution_mm = 0.2;
  double station0_mm = 0.0;
  int rows = 0;
  int cols = 0;

  [[nodiscard]] double RowStationMm(int row) const {
    return station0_mm + (row + 0.5) * resolution_mm;
  }
  [[nodiscard]] double ColClockRad(int col) const;
  /// Rows [first_row, first_row + rows) of this grid as a grid of their own (a tile).
  [[nodiscard]] MapGrid Tile(int first_row, int tile_rows) const;
};

/// The grid over stations [begin_mm, end_mm) (rows = ceil(length / resolution)) of a pipe of
/// model radius `radius_mm`: cols = round(2π radius / resolution).
MapGrid MakeMapGrid(double begin_mm, double end_mm, double radius_mm, double resolution_mm);

enum class Coverage : unsigned char { kNone = 0, kMeasured = 1, kFilled = 2 };

/// One tile (or the whole) of the maps, rows × cols of `grid`.
struct PipeMaps {
  MapGrid grid;
  cv::Mat3b texture;          ///< BGR, mean colour per cell (black where none)
  cv::Mat1f displacement_mm;  ///< measured − model radius, positive outward; NaN = none
  cv::Mat1w samples;          ///< points that fell in the cell (saturating)
  cv::Mat1b coverage;         ///< Coverage values
};

}  // namespace sewer3d
