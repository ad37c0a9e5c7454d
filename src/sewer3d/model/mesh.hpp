#pragma once
/// \file
/// Triangle meshes of the pipe model (paper §4.4, "a cylindrical mesh with a detailed texture
/// and displacement map"; DESIGN.md "processing workspace": mesh.obj, mesh.glb): the base
/// cylinder along the centreline with UVs into the texture map, and a mesh with the
/// displacement map baked in (glTF has no displacement maps), decimated to a size a browser
/// opens. Also the point-sampled surface (one point per covered map cell, surface.ply).
///
/// UVs follow the image convention of the texture map (and glTF): u = clock / 2π (= column /
/// cols), v = (station − grid.station0) / (rows · resolution) (= row / rows, 0 at the top row).
/// Triangles wind counter-clockwise seen from inside the pipe, and normals point inward
/// (toward the axis: the side of the wall the robot saw).

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sewer3d/model/pipe_map.hpp"

namespace sewer3d {

/// An indexed triangle mesh: positions in mm in the model frame, unit normals, UVs.
struct TriangleMesh {
  std::vector<Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3f> normals;
  std::vector<Eigen::Vector2f> uvs;
  std::vector<std::array<std::uint32_t, 3>> triangles;

  [[nodiscard]] std::size_t VertexCount() const { return positions.size(); }
};

struct BaseCylinderOptions {
  int segments = 360;          ///< vertices around (the seam vertex at the crown is extra)
  double ring_step_mm = 10.0;  ///< largest station step between rings (evenly spaced)
  void Check() const;
};

/// The cylinder of radius `centreline.radius_mm` along the centreline over the grid's stations
/// (grid.station0_mm … + rows · resolution_mm), segments + 1 vertices per ring (the crown
/// vertex duplicated with u = 0 and u = 1 so the texture wraps). Needs grid.rows, cols > 0 and
/// a centreline of at least 2 samples.
TriangleMesh BuildBaseCylinder(const Centreline& centreline, const MapGrid& grid,
                               const BaseCylinderOptions& options);

struct DisplacedMeshOptions {
  double step_mm = 2.0;  ///< vertex spacing, along the pipe and around (at the model radius)
  std::size_t max_vertices = 2'000'000;  ///< budget (a browser opens ~2 M vertices)
  /// When the lattice at step_mm exceeds the budget: true = coarsen the step until it fits,
  /// false = return no mesh (DisplacedMeshResult::within_budget false).
  bool coarsen_to_fit = true;
  void Check() const;
};

/// The smallest step ≥ `step_mm` whose vertex lattice over `grid` has ≤ `max_vertices`.
double DisplacedMeshStepMm(const MapGrid& grid, double step_mm, std::size_t max_vertices);

/// Accumulates the displacement map of a whole run, tile by tile (bounded memory: only the
/// decimated lattice is held), into the vertex lattice of the displaced mesh: rings + 1 rings
/// evenly spaced over the run's stations, `around` vertices evenly spaced over the clock,
/// each the mean of the cells nearest to it (a box filter one step wide). A vertex without
/// any finite cell has no data.
class DisplacementDecimator {
 public:
  /// `run_grid`: the whole run's grid; options checked here.
  DisplacementDecimator(const MapGrid& run_grid, const DisplacedMeshOptions& options);

  /// Adds a tile (or the whole) of the maps: same resolution and cols as the run grid, rows
  /// within it (its station0 a whole number of rows from the run's). Only displacement_mm is
  /// read.
  void Add(const PipeMaps& tile);

  [[nodiscard]] double step_mm() const { return step_mm_; }
  [[nodiscard]] int rings() const { return rings_; }
  [[nodiscard]] int around() const { return around_; }
  [[nodiscard]] bool within_budget() const { return within_budget_; }
  /// Station of ring `ring` (0 … rings): evenly spaced from the run grid's first to last edge.
  [[nodiscard]] double RingStationMm(int ring) const;
  /// Mean displacement of lattice vertex (ring, j); NaN without data.
  [[nodiscard]] double MeanMm(int ring, int j) const;

 private:
  MapGrid grid_;
  double step_mm_ = 0.0;
  int rings_ = 0, around_ = 0;
  bool within_budget_ = true;
  std::vector<double> sum_mm_;
  std::vector<std::uint32_t> count_;
};

struct DisplacedMeshResult {
  TriangleMesh mesh;  ///< empty when !within_budget
  double step_mm = 0.0;
  int rings = 0;   ///< ring intervals along the pipe (rings + 1 rings of vertices)
  int around = 0;  ///< vertices around (plus the seam duplicate)
  bool within_budget = true;
  std::size_t lattice_vertices = 0;  ///< (rings + 1) · (around + 1), with and without data
};

/// The displaced mesh from an accumulated lattice: each vertex at centreline(station) +
/// (radius + mean displacement) · direction(clock); triangles only where all three vertices
/// have data; vertices without data dropped; normals from the triangles (area-weighted,
/// continuous across the seam).
DisplacedMeshResult BuildDisplacedMesh(const Centreline& centreline,
                                       const DisplacementDecimator& lattice);

/// Shorthand for a run whose maps are in memory: one DisplacementDecimator over `maps`.
DisplacedMeshResult BuildDisplacedMesh(const Centreline& centreline, const PipeMaps& maps,
                                       const DisplacedMeshOptions& options);

/// The point-sampled surface: one point per cell with coverage ≠ none and a finite
/// displacement, at centreline(station) + (radius + d) · direction(clock) (model frame, mm),
/// with its texture colour as RGB.
struct SurfacePoints {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<std::uint8_t, 3>> colours_rgb;
};
SurfacePoints MapSurfacePoints(const Centreline& centreline, const PipeMaps& maps);

}  // namespace sewer3d
