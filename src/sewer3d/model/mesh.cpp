#include "sewer3d/model/mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

double LengthMm(const MapGrid& grid) { return grid.rows * grid.resolution_mm; }
double CircumferenceMm(const MapGrid& grid) { return grid.cols * grid.resolution_mm; }

int RingsFor(const MapGrid& grid, double step_mm) {
  return std::max(1, static_cast<int>(std::lround(LengthMm(grid) / step_mm)));
}
int AroundFor(const MapGrid& grid, double step_mm) {
  return std::max(3, static_cast<int>(std::lround(CircumferenceMm(grid) / step_mm)));
}
std::size_t LatticeVertices(int rings, int around) {
  return static_cast<std::size_t>(rings + 1) * static_cast<std::size_t>(around + 1);
}

void CheckGrid(const MapGrid& grid) {
  SEWER3D_CHECK(grid.rows > 0 && grid.cols > 0 && grid.resolution_mm > 0.0,
                "map grid " << grid.rows << " x " << grid.cols << " at " << grid.resolution_mm);
}

// Two triangles per lattice quad (ring i → i + 1, column j → j + 1), counter-clockwise seen
// from inside: along the pipe × around the clock points toward the axis (see mesh.hpp).
template <typename Emit>
void ForEachQuadTriangle(std::size_t a, std::size_t b, std::size_t c, std::size_t d, Emit&& emit) {
  emit(a, b, c);  // (i, j), (i + 1, j), (i, j + 1)
  emit(c, b, d);  // (i, j + 1), (i + 1, j), (i + 1, j + 1)
}

}  // namespace

void BaseCylinderOptions::Check() const {
  SEWER3D_VALIDATE(segments >= 3, "segments", "must be >= 3, got " << segments);
  ValidatePositive("ring_step_mm", ring_step_mm);
}

void DisplacedMeshOptions::Check() const {
  ValidatePositive("step_mm", step_mm);
  SEWER3D_VALIDATE(max_vertices >= 64, "max_vertices", "must be >= 64, got " << max_vertices);
}

TriangleMesh BuildBaseCylinder(const Centreline& centreline, const MapGrid& grid,
                               const BaseCylinderOptions& options) {
  options.Check();
  CheckGrid(grid);
  const int rings = std::max(1, static_cast<int>(std::ceil(LengthMm(grid) / options.ring_step_mm)));
  const int n = options.segments;
  TriangleMesh mesh;
  for (int i = 0; i <= rings; ++i) {
    const double v = static_cast<double>(i) / rings;
    const AxisFrame frame = centreline.FrameAt(grid.station0_mm + v * LengthMm(grid));
    for (int j = 0; j <= n; ++j) {
      const double u = static_cast<double>(j) / n;
      const Eigen::Vector3d direction = frame.Direction(u * kTwoPi);
      mesh.positions.push_back((frame.origin + centreline.radius_mm * direction).cast<float>());
      mesh.normals.push_back((-direction).cast<float>());
      mesh.uvs.emplace_back(static_cast<float>(u), static_cast<float>(v));
    }
  }
  const auto at = [n](int i, int j) { return static_cast<std::uint32_t>(i * (n + 1) + j); };
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < n; ++j) {
      ForEachQuadTriangle(
          at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1),
          [&](std::size_t a, std::size_t b, std::size_t c) {
            mesh.triangles.push_back({static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b),
                                      static_cast<std::uint32_t>(c)});
          });
    }
  }
  return mesh;
}

double DisplacedMeshStepMm(const MapGrid& grid, double step_mm, std::size_t max_vertices) {
  CheckGrid(grid);
  SEWER3D_CHECK(step_mm > 0.0 && max_vertices >= 64);
  double step = step_mm;
  if (LatticeVertices(RingsFor(grid, step), AroundFor(grid, step)) <= max_vertices) return step;
  // (L/s + 1)(C/s + 1) ≤ N  ⇔  (N − 1) s² − (L + C) s − L C ≥ 0: its positive root, then a few
  // 1 % steps for the rounding of the ring and segment counts.
  const double l = LengthMm(grid), c = CircumferenceMm(grid);
  const double n1 = static_cast<double>(max_vertices) - 1.0;
  step = std::max(step, ((l + c) + std::sqrt((l + c) * (l + c) + 4.0 * n1 * l * c)) / (2.0 * n1));
  while (LatticeVertices(RingsFor(grid, step), AroundFor(grid, step)) > max_vertices) {
    step *= 1.01;
  }
  return step;
}

DisplacementDecimator::DisplacementDecimator(const MapGrid& run_grid,
                                             const DisplacedMeshOptions& options)
    : grid_(run_grid) {
  options.Check();
  CheckGrid(run_grid);
  step_mm_ = options.coarsen_to_fit
                 ? DisplacedMeshStepMm(run_grid, options.step_mm, options.max_vertices)
                 : options.step_mm;
  rings_ = RingsFor(run_grid, step_mm_);
  around_ = AroundFor(run_grid, step_mm_);
  within_budget_ = LatticeVertices(rings_, around_) <= options.max_vertices;
  if (!within_budget_) return;  // nothing to accumulate: no mesh will be built
  const auto size = static_cast<std::size_t>(rings_ + 1) * static_cast<std::size_t>(around_);
  sum_mm_.assign(size, 0.0);
  count_.assign(size, 0);
}

void DisplacementDecimator::Add(const PipeMaps& tile) {
  if (!within_budget_) return;
  const MapGrid& g = tile.grid;
  const double offset_rows = (g.station0_mm - grid_.station0_mm) / grid_.resolution_mm;
  const int row0 = static_cast<int>(std::lround(offset_rows));
  SEWER3D_CHECK(std::abs(g.resolution_mm - grid_.resolution_mm) < 1e-9 && g.cols == grid_.cols &&
                    std::abs(offset_rows - row0) < 1e-6 && row0 >= 0 && row0 + g.rows <= grid_.rows,
                "tile rows " << row0 << " + " << g.rows << " outside the run's " << grid_.rows);
  SEWER3D_CHECK(tile.displacement_mm.rows == g.rows && tile.displacement_mm.cols == g.cols);
  // The nearest lattice column of each map column (wrapping at the crown) and ring of each row.
  std::vector<int> column_to_j(g.cols);
  for (int c = 0; c < g.cols; ++c) {
    column_to_j[c] = static_cast<int>(std::lround((c + 0.5) * around_ / g.cols)) % around_;
  }
  for (int r = 0; r < g.rows; ++r) {
    const double x = (row0 + r + 0.5) / grid_.rows;
    const int ring = std::clamp(static_cast<int>(std::lround(x * rings_)), 0, rings_);
    const float* d = tile.displacement_mm[r];
    for (int c = 0; c < g.cols; ++c) {
      if (!std::isfinite(d[c])) continue;
      const std::size_t k = static_cast<std::size_t>(ring) * around_ + column_to_j[c];
      sum_mm_[k] += d[c];
      ++count_[k];
    }
  }
}

double DisplacementDecimator::RingStationMm(int ring) const {
  return grid_.station0_mm + LengthMm(grid_) * ring / rings_;
}

double DisplacementDecimator::MeanMm(int ring, int j) const {
  SEWER3D_CHECK(within_budget_ && ring >= 0 && ring <= rings_ && j >= 0 && j < around_);
  const std::size_t k = static_cast<std::size_t>(ring) * around_ + j;
  return count_[k] == 0 ? std::numeric_limits<double>::quiet_NaN() : sum_mm_[k] / count_[k];
}

DisplacedMeshResult BuildDisplacedMesh(const Centreline& centreline,
                                       const DisplacementDecimator& lattice) {
  DisplacedMeshResult result;
  result.step_mm = lattice.step_mm();
  result.rings = lattice.rings();
  result.around = lattice.around();
  result.within_budget = lattice.within_budget();
  const int rings = result.rings, around = result.around;
  result.lattice_vertices = LatticeVertices(rings, around);
  if (!result.within_budget) return result;
  // Lattice vertices (i, j), j = 0 … around (j = around duplicates the crown with u = 1).
  const auto at = [around](int i, int j) {
    return static_cast<std::size_t>(i) * (around + 1) + static_cast<std::size_t>(j);
  };
  std::vector<Eigen::Vector3d> position(result.lattice_vertices);
  std::vector<char> has_data(result.lattice_vertices, 0);
  for (int i = 0; i <= rings; ++i) {
    const AxisFrame frame = centreline.FrameAt(lattice.RingStationMm(i));
    for (int j = 0; j <= around; ++j) {
      const double d = lattice.MeanMm(i, j % around);
      if (!std::isfinite(d)) continue;
      const double clock = kTwoPi * j / around;
      position[at(i, j)] = frame.origin + (centreline.radius_mm + d) * frame.Direction(clock);
      has_data[at(i, j)] = 1;
    }
  }
  // Triangles where all three corners have data, in lattice indices; face normals (area-
  // weighted) summed per vertex with the seam's two copies as one vertex.
  std::vector<std::array<std::size_t, 3>> faces;
  std::vector<Eigen::Vector3d> normal_sum(result.lattice_vertices, Eigen::Vector3d::Zero());
  const auto canonical = [&](std::size_t k) {
    return k % (around + 1) == static_cast<std::size_t>(around) ? k - around : k;
  };
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < around; ++j) {
      ForEachQuadTriangle(at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1),
                          [&](std::size_t a, std::size_t b, std::size_t c) {
                            if (!has_data[a] || !has_data[b] || !has_data[c]) return;
                            faces.push_back({a, b, c});
                            const Eigen::Vector3d n =
                                (position[b] - position[a]).cross(position[c] - position[a]);
                            for (std::size_t k : {a, b, c}) normal_sum[canonical(k)] += n;
                          });
    }
  }
  // Keep the vertices that some triangle uses, in lattice order.
  constexpr auto kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> index(result.lattice_vertices, kUnused);
  for (const auto& f : faces) {
    for (std::size_t k : f) index[k] = 0;
  }
  TriangleMesh& mesh = result.mesh;
  for (int i = 0; i <= rings; ++i) {
    for (int j = 0; j <= around; ++j) {
      const std::size_t k = at(i, j);
      if (index[k] == kUnused) continue;
      index[k] = static_cast<std::uint32_t>(mesh.positions.size());
      mesh.positions.push_back(position[k].cast<float>());
      mesh.normals.push_back(normal_sum[canonical(k)].normalized().cast<float>());
      mesh.uvs.emplace_back(static_cast<float>(static_cast<double>(j) / around),
                            static_cast<float>(static_cast<double>(i) / rings));
    }
  }
  mesh.triangles.reserve(faces.size());
  for (const auto& f : faces) mesh.triangles.push_back({index[f[0]], index[f[1]], index[f[2]]});
  return result;
}

DisplacedMeshResult BuildDisplacedMesh(const Centreline& centreline, const PipeMaps& maps,
                                       const DisplacedMeshOptions& options) {
  DisplacementDecimator lattice(maps.grid, options);
  lattice.Add(maps);
  return BuildDisplacedMesh(centreline, lattice);
}

SurfacePoints MapSurfacePoints(const Centreline& centreline, const PipeMaps& maps) {
  const MapGrid& g = maps.grid;
  CheckGrid(g);
  SEWER3D_CHECK(maps.displacement_mm.rows == g.rows && maps.displacement_mm.cols == g.cols &&
                maps.coverage.size() == maps.displacement_mm.size() &&
                maps.texture.size() == maps.displacement_mm.size());
  std::vector<double> cos_clock(g.cols), sin_clock(g.cols);
  for (int c = 0; c < g.cols; ++c) {
    cos_clock[c] = std::cos(g.ColClockRad(c));
    sin_clock[c] = std::sin(g.ColClockRad(c));
  }
  SurfacePoints out;
  for (int r = 0; r < g.rows; ++r) {
    const AxisFrame frame = centreline.FrameAt(g.RowStationMm(r));
    for (int c = 0; c < g.cols; ++c) {
      const float d = maps.displacement_mm(r, c);
      if (maps.coverage(r, c) == static_cast<unsigned char>(Coverage::kNone) || !std::isfinite(d))
        continue;
      const Eigen::Vector3d direction = cos_clock[c] * frame.crown + sin_clock[c] * frame.right;
      out.points.push_back(frame.origin + (centreline.radius_mm + d) * direction);
      const cv::Vec3b bgr = maps.texture(r, c);
      out.colours_rgb.push_back({bgr[2], bgr[1], bgr[0]});
    }
  }
  return out;
}

}  // namespace sewer3d
