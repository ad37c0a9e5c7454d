// Meshes of the pipe model: the base cylinder lies on the model radius around the centreline
// (straight and bent) with UVs into the texture map and a duplicated seam; the displaced mesh
// puts each vertex at radius + the mean displacement of its cells, leaves holes open, stays
// within its vertex budget and does not depend on how the run was cut into tiles; the
// point-sampled surface has one point per covered cell at radius + displacement.

#include "sewer3d/model/mesh.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <numbers>
#include <opencv2/core.hpp>
#include <stdexcept>

namespace sewer3d {
namespace {

constexpr double kRadius = 150.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A 100 mm long map at 1 mm: 100 rows × 942 columns (round(2π · 150)).
MapGrid SmallGrid() {
  MapGrid g;
  g.resolution_mm = 1.0;
  g.station0_mm = 40.0;
  g.rows = 100;
  g.cols = static_cast<int>(std::lround(2.0 * std::numbers::pi * kRadius / g.resolution_mm));
  return g;
}

// Straight along +z, or an arc of radius `bend_mm` in the x–z plane; crown straight up (−y).
Centreline MakeCentreline(double bend_mm) {
  Centreline line;
  line.station0_mm = 0.0;
  line.step_mm = 10.0;
  line.radius_mm = kRadius;
  for (int i = 0; i <= 20; ++i) {
    const double s = i * line.step_mm;
    line.points.push_back(bend_mm > 0.0 ? Eigen::Vector3d(bend_mm * (1.0 - std::cos(s / bend_mm)),
                                                          0.0, bend_mm * std::sin(s / bend_mm))
                                        : Eigen::Vector3d(0.0, 0.0, s));
    line.crowns.push_back(-Eigen::Vector3d::UnitY());
  }
  return line;
}

PipeMaps MapsWith(const MapGrid& grid, double displacement_mm) {
  PipeMaps maps;
  maps.grid = grid;
  maps.texture = cv::Mat3b(grid.rows, grid.cols, cv::Vec3b(10, 20, 30));
  maps.displacement_mm = cv::Mat1f(grid.rows, grid.cols, static_cast<float>(displacement_mm));
  maps.samples = cv::Mat1w(grid.rows, grid.cols, 3);
  maps.coverage = cv::Mat1b(grid.rows, grid.cols, static_cast<unsigned char>(Coverage::kMeasured));
  return maps;
}

// The station a vertex lies at, from its v coordinate.
double StationOf(const MapGrid& grid, const Eigen::Vector2f& uv) {
  return grid.station0_mm + uv.y() * grid.rows * grid.resolution_mm;
}

// Distance from `p` to the axis point at its station, and its offset along the tangent.
std::pair<double, double> RadialAndAxial(const Centreline& line, double station,
                                         const Eigen::Vector3f& p) {
  const AxisFrame f = line.FrameAt(station);
  const Eigen::Vector3d d = p.cast<double>() - f.origin;
  return {d.norm(), d.dot(f.tangent)};
}

TEST(BaseCylinder, VerticesOnTheRadiusWithWrappingUvs) {
  for (double bend_mm : {0.0, 2000.0}) {
    const Centreline line = MakeCentreline(bend_mm);
    const MapGrid grid = SmallGrid();
    const BaseCylinderOptions options{.segments = 256, .ring_step_mm = 10.0};
    const TriangleMesh mesh = BuildBaseCylinder(line, grid, options);
    ASSERT_EQ(mesh.VertexCount(), 11u * 257u);
    ASSERT_EQ(mesh.triangles.size(), 10u * 256u * 2u);
    for (std::size_t k = 0; k < mesh.VertexCount(); ++k) {
      const auto [radial, axial] =
          RadialAndAxial(line, StationOf(grid, mesh.uvs[k]), mesh.positions[k]);
      ASSERT_NEAR(radial, kRadius, 1e-4) << "vertex " << k << " bend " << bend_mm;
      ASSERT_NEAR(axial, 0.0, 1e-4);
      const Eigen::Vector3d inward =
          line.FrameAt(StationOf(grid, mesh.uvs[k])).origin - mesh.positions[k].cast<double>();
      ASSERT_GT(mesh.normals[k].cast<double>().dot(inward.normalized()), 1.0 - 1e-6);
    }
    // The seam: the first and last vertex of a ring coincide, with u = 0 and u = 1; v spans
    // the map's rows.
    EXPECT_LT((mesh.positions[0] - mesh.positions[256]).norm(), 1e-4);
    EXPECT_EQ(mesh.uvs[0].x(), 0.0f);
    EXPECT_EQ(mesh.uvs[256].x(), 1.0f);
    EXPECT_EQ(mesh.uvs.back().y(), 1.0f);
    // u = 0.25 is 3 o'clock: +x on the straight pipe (crown −y, axis +z).
    if (bend_mm == 0.0) {
      EXPECT_NEAR(mesh.positions[64].x(), kRadius, 1e-4);
    }
  }
}

TEST(BaseCylinder, TrianglesFaceTheAxis) {
  const Centreline line = MakeCentreline(0.0);
  const TriangleMesh mesh = BuildBaseCylinder(line, SmallGrid(), {});
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3f a = mesh.positions[t[0]], b = mesh.positions[t[1]],
                          c = mesh.positions[t[2]];
    const Eigen::Vector3f n = (b - a).cross(c - a);
    ASSERT_GT(n.dot(mesh.normals[t[0]]), 0.0f);
  }
}

TEST(DisplacedMesh, VerticesAtRadiusPlusDisplacementWithHolesOpen) {
  const Centreline line = MakeCentreline(2000.0);
  const MapGrid grid = SmallGrid();
  PipeMaps maps = MapsWith(grid, 3.0);
  // A 20 × 20 mm hole without data.
  maps.displacement_mm(cv::Rect(100, 40, 20, 20)).setTo(kNaN);
  const DisplacedMeshResult result = BuildDisplacedMesh(line, maps, {.step_mm = 2.0});
  ASSERT_TRUE(result.within_budget);
  EXPECT_EQ(result.rings, 50);
  EXPECT_EQ(result.around, 471);
  EXPECT_EQ(result.lattice_vertices, 51u * 472u);
  const TriangleMesh& mesh = result.mesh;
  // The hole's 9 × 9 interior lattice vertices have no data (the box filter sees no cell).
  EXPECT_EQ(mesh.VertexCount(), 51u * 472u - 81u);
  // The 10 × 10 quads around them lose their triangles, but for one at each of two corners
  // whose three vertices all have data.
  EXPECT_EQ(mesh.triangles.size(), 50u * 471u * 2u - 10u * 10u * 2u + 2u);
  for (std::size_t k = 0; k < mesh.VertexCount(); ++k) {
    const auto [radial, axial] =
        RadialAndAxial(line, StationOf(grid, mesh.uvs[k]), mesh.positions[k]);
    ASSERT_NEAR(radial, kRadius + 3.0, 1e-4) << "vertex " << k;
    ASSERT_NEAR(axial, 0.0, 1e-4);
    const Eigen::Vector3d inward =
        line.FrameAt(StationOf(grid, mesh.uvs[k])).origin - mesh.positions[k].cast<double>();
    ASSERT_GT(mesh.normals[k].cast<double>().dot(inward.normalized()), 0.999) << "vertex " << k;
  }
}

TEST(DisplacedMesh, VertexIsTheMeanOfItsCells) {
  const Centreline line = MakeCentreline(0.0);
  const MapGrid grid = SmallGrid();
  PipeMaps maps = MapsWith(grid, 0.0);
  // Linear in station: a box filter centred on a ring returns the value at the ring's station.
  for (int r = 0; r < grid.rows; ++r) maps.displacement_mm.row(r).setTo(0.05 * (r + 0.5) - 2.0);
  const DisplacedMeshResult result = BuildDisplacedMesh(line, maps, {.step_mm = 4.0});
  for (std::size_t k = 0; k < result.mesh.VertexCount(); ++k) {
    const double station = StationOf(grid, result.mesh.uvs[k]);
    if (station <= grid.station0_mm || station >= grid.station0_mm + 100.0) continue;  // half box
    const double expected = 0.05 * (station - grid.station0_mm) - 2.0;
    const auto [radial, axial] = RadialAndAxial(line, station, result.mesh.positions[k]);
    ASSERT_NEAR(radial - kRadius, expected, 1e-4) << "station " << station;
  }
}

TEST(DisplacedMesh, TilesGiveTheSameLatticeAsTheWholeMap) {
  const MapGrid grid = SmallGrid();
  PipeMaps whole = MapsWith(grid, 0.0);
  cv::randu(whole.displacement_mm, -5.0, 5.0);
  DisplacementDecimator from_whole(grid, {.step_mm = 3.0});
  from_whole.Add(whole);
  DisplacementDecimator from_tiles(grid, {.step_mm = 3.0});
  for (int row0 : {0, 37}) {
    PipeMaps tile;
    tile.grid = grid;
    tile.grid.station0_mm = grid.station0_mm + row0 * grid.resolution_mm;
    tile.grid.rows = row0 == 0 ? 37 : grid.rows - 37;
    tile.displacement_mm = whole.displacement_mm.rowRange(row0, row0 + tile.grid.rows).clone();
    from_tiles.Add(tile);
  }
  for (int i = 0; i <= from_whole.rings(); ++i) {
    for (int j = 0; j < from_whole.around(); ++j)
      ASSERT_NEAR(from_tiles.MeanMm(i, j), from_whole.MeanMm(i, j), 1e-12);
  }
}

TEST(DisplacedMesh, StaysWithinItsVertexBudget) {
  const Centreline line = MakeCentreline(0.0);
  const PipeMaps maps = MapsWith(SmallGrid(), 1.0);
  const DisplacedMeshResult coarse = BuildDisplacedMesh(line, maps, {.max_vertices = 5000});
  EXPECT_TRUE(coarse.within_budget);
  EXPECT_GT(coarse.step_mm, 2.0);
  EXPECT_LE(coarse.lattice_vertices, 5000u);
  EXPECT_GT(coarse.lattice_vertices, 4000u);  // not coarser than needed
  EXPECT_EQ(coarse.mesh.VertexCount(), coarse.lattice_vertices);
  const DisplacedMeshResult refused =
      BuildDisplacedMesh(line, maps, {.max_vertices = 5000, .coarsen_to_fit = false});
  EXPECT_FALSE(refused.within_budget);
  EXPECT_TRUE(refused.mesh.positions.empty());
  // 10 m of DN300 at 2 mm would be 5001 × 472 vertices: coarsened to fit 2 M.
  MapGrid long_run = SmallGrid();
  long_run.rows = 50000;
  long_run.resolution_mm = 0.2;
  long_run.cols = 4712;
  EXPECT_GT(DisplacedMeshStepMm(long_run, 2.0, 2'000'000), 2.0);
  EXPECT_EQ(DisplacedMeshStepMm(long_run, 2.0, 3'000'000), 2.0);
}

TEST(DisplacedMesh, OptionsAreChecked) {
  EXPECT_THROW((DisplacedMeshOptions{.step_mm = 0.0}.Check()), std::invalid_argument);
  EXPECT_THROW((DisplacedMeshOptions{.max_vertices = 10}.Check()), std::invalid_argument);
  EXPECT_THROW((BaseCylinderOptions{.segments = 2}.Check()), std::invalid_argument);
  EXPECT_THROW((BaseCylinderOptions{.ring_step_mm = -1.0}.Check()), std::invalid_argument);
}

TEST(SurfacePoints, OnePointPerCoveredCellAtRadiusPlusDisplacement) {
  const Centreline line = MakeCentreline(2000.0);
  PipeMaps maps = MapsWith(SmallGrid(), -1.25);
  maps.coverage(cv::Rect(0, 0, 300, 10)).setTo(0);              // 3000 cells not covered
  maps.displacement_mm(cv::Rect(500, 50, 10, 10)).setTo(kNaN);  // 100 covered, no value
  maps.coverage(cv::Rect(0, 90, 942, 10)).setTo(static_cast<unsigned char>(Coverage::kFilled));
  const SurfacePoints surface = MapSurfacePoints(line, maps);
  ASSERT_EQ(surface.points.size(), 100u * 942u - 3000u - 100u);
  ASSERT_EQ(surface.colours_rgb.size(), surface.points.size());
  EXPECT_EQ(surface.colours_rgb[0][0], 30);  // RGB from the BGR texture
  const MapGrid& g = maps.grid;
  const AxisFrame f = line.FrameAt(g.RowStationMm(0));  // first point: row 0, column 300
  EXPECT_NEAR((surface.points[0] - f.origin).norm(), kRadius - 1.25, 1e-9);
  EXPECT_NEAR((surface.points[0] - f.origin).normalized().dot(f.Direction(g.ColClockRad(300))), 1.0,
              1e-12);
}

}  // namespace
}  // namespace sewer3d
