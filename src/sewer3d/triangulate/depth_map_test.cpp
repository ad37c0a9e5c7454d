// Depth-map interpolation on a tilted plane seen by a pinhole camera, where inverse depth is
// an affine function of the pixel: the map must be exact to float precision inside triangles,
// empty across long edges, and tight enough to tell 1/z interpolation from linear z.

#include "sewer3d/triangulate/depth_map.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <string>

#include "sewer3d/core/check.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/testing/small_module.hpp"

namespace sewer3d {
namespace {

// The plane n · X = d (camera frame, mm) through a pinhole camera of focal f px, centre c:
// z = d / (n · ray) from 64 to 182 mm over a 640 x 480 image.
struct TiltedPlane {
  Eigen::Vector3d normal = Eigen::Vector3d(0.6, 0.2, 1.0).normalized();  // 32° from the axis
  double distance_mm = 80.0;
  double focal_px = 500.0;
  Eigen::Vector2d centre_px{320.0, 240.0};

  double Depth(const Eigen::Vector2d& px) const {
    const Eigen::Vector3d ray(((px - centre_px) / focal_px).x(), ((px - centre_px) / focal_px).y(),
                              1.0);
    return distance_mm / normal.dot(ray);
  }
};

// Float precision of a depth: the map stores float, so half an ulp of the rounding plus the
// double arithmetic before it; 2 ulps covers both.
double FloatTolerance(double z_mm) { return 2.0 * FLT_EPSILON * z_mm; }

TEST(DepthMap, TiltedPlaneIsExactToFloatPrecisionInsideTriangles) {
  const TiltedPlane plane;
  const cv::Size size(640, 480);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-2.0, 2.0);
  std::vector<Eigen::Vector2d> pixels;
  std::vector<double> depths;
  for (double v = 20.0; v <= 460.0; v += 8.0) {
    for (double u = 20.0; u <= 620.0; u += 8.0) {
      pixels.emplace_back(u + jitter(rng), v + jitter(rng));
      depths.push_back(plane.Depth(pixels.back()));
    }
  }
  // Jittered 8 px grid: Delaunay edges are at most ~16 px.
  const cv::Mat1f depth = InterpolateDepth(size, pixels, depths, 20.0);
  double worst_ulps = 0.0;
  for (int v = 0; v < size.height; ++v) {
    for (int u = 0; u < size.width; ++u) {
      // Inside the jittered grid (2 px from its outer points' extremes) every pixel has depth.
      if (u >= 24 && u <= 616 && v >= 24 && v <= 456) {
        ASSERT_FALSE(std::isnan(depth(v, u))) << u << ", " << v;
      }
      if (std::isnan(depth(v, u))) continue;
      const double truth = plane.Depth({u, v});
      worst_ulps = std::max(worst_ulps, std::abs(depth(v, u) - truth) / (FLT_EPSILON * truth));
      ASSERT_LE(std::abs(depth(v, u) - truth), FloatTolerance(truth)) << u << ", " << v;
    }
  }
  RecordProperty("worst_error_in_float_epsilons", std::to_string(worst_ulps));
}

TEST(DepthMap, LinearDepthWouldMissTheTolerance) {
  // One triangle of the grid's size on the same plane: z interpolated linearly between its
  // corners departs from the plane by z'' h² / 8 ≈ hundredths of a millimetre, far above float
  // precision, while 1/z interpolation (what InterpolateDepth does) stays exact.
  const TiltedPlane plane;
  const std::vector<Eigen::Vector2d> pixels{{100.0, 100.0}, {116.0, 100.0}, {100.0, 116.0}};
  std::vector<double> depths;
  for (const auto& p : pixels) depths.push_back(plane.Depth(p));
  const cv::Mat1f depth = InterpolateDepth({200, 200}, pixels, depths, 30.0);
  double worst_map = 0.0, worst_linear = 0.0;
  int inside = 0;
  for (int v = 100; v <= 116; ++v) {
    for (int u = 100; u <= 116; ++u) {
      const double wb = (u - 100.0) / 16.0, wc = (v - 100.0) / 16.0, wa = 1.0 - wb - wc;
      if (wa < 0.0) {
        EXPECT_TRUE(std::isnan(depth(v, u))) << u << ", " << v;
        continue;
      }
      ++inside;
      const double truth = plane.Depth({u, v});
      const double linear = wa * depths[0] + wb * depths[1] + wc * depths[2];
      ASSERT_FALSE(std::isnan(depth(v, u))) << u << ", " << v;
      worst_map = std::max(worst_map, std::abs(depth(v, u) - truth) / FloatTolerance(truth));
      worst_linear = std::max(worst_linear, std::abs(linear - truth) / FloatTolerance(truth));
    }
  }
  EXPECT_EQ(inside, 17 * 18 / 2);
  EXPECT_LE(worst_map, 1.0);
  EXPECT_GT(worst_linear, 100.0);
  RecordProperty("linear_z_error_in_tolerances", std::to_string(worst_linear));
}

TEST(DepthMap, TrianglesWithALongEdgeStayEmpty) {
  const TiltedPlane plane;
  // Two patches of an 8 px grid 60 px apart: the triangles bridging the gap have edges of at
  // least 60 px.
  std::vector<Eigen::Vector2d> pixels;
  std::vector<double> depths;
  for (double v = 100.0; v <= 200.0; v += 8.0) {
    for (double u : {100.0, 108.0, 116.0, 124.0, 184.0, 192.0, 200.0, 208.0}) {
      pixels.emplace_back(u, v + 0.25 * u / 8.0);  // sheared: no four points on a circle
      depths.push_back(plane.Depth(pixels.back()));
    }
  }
  const cv::Mat1f depth = InterpolateDepth({320, 320}, pixels, depths, 20.0);
  for (int v = 120; v <= 180; ++v) {
    EXPECT_FALSE(std::isnan(depth(v, 112))) << v;  // inside a patch
    EXPECT_FALSE(std::isnan(depth(v, 196))) << v;
    for (int u = 125; u <= 183; ++u) ASSERT_TRUE(std::isnan(depth(v, u))) << u << ", " << v;
  }
  // The same points with a limit above the gap fill it.
  const cv::Mat1f bridged = InterpolateDepth({320, 320}, pixels, depths, 80.0);
  EXPECT_FALSE(std::isnan(bridged(150, 150)));
  // And one triangle whose longest edge (22.6 px) exceeds the limit leaves everything empty.
  const cv::Mat1f none =
      InterpolateDepth({64, 64}, {{10, 10}, {26, 10}, {10, 26}}, {100.0, 100.0, 100.0}, 20.0);
  EXPECT_EQ(cv::countNonZero(none == none), 0);  // NaN != NaN
}

// The default pattern on the 648 px default module, its lit elements meshed.
struct MeshedPattern {
  ModuleDescription module = testing::SmallDefaultModule(648);
  BinaryArray pattern = DefaultPatternArray();
  ElementMesh mesh = MeshLitElements(module, pattern);
};

// The module's lit elements, meshed: every lit element on the projector image is a vertex,
// and no triangle holds another lit element (inside or on an edge).
TEST(ElementMesh, JoinsNeighbouringLitElementsOnly) {
  const MeshedPattern meshed;
  const BinaryArray& pattern = meshed.pattern;
  const ElementMesh& mesh = meshed.mesh;
  ASSERT_GT(mesh.rows, 0);
  std::vector<int> degree(static_cast<size_t>(mesh.rows) * mesh.cols, 0);
  const auto at = [&](int k) { return Eigen::Vector2d(k % mesh.cols, k / mesh.cols); };
  for (const auto& t : mesh.triangles) {
    for (int k : t) ++degree[k];
    const Eigen::Vector2d a = at(t[0]), b = at(t[1]), c = at(t[2]);
    const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    ASSERT_GT(area, 0.0);  // counter-clockwise in (column, row)
    const Eigen::Vector2d lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
    for (int r = int(lo.y()); r <= int(hi.y()); ++r) {
      for (int col = int(lo.x()); col <= int(hi.x()); ++col) {
        const Eigen::Vector2d p(col, r);
        if (p == a || p == b || p == c) continue;
        if (!pattern.tiled(r + mesh.row0, col + mesh.col0)) continue;
        const auto side = [&](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
          return (v - u).x() * (p - u).y() - (v - u).y() * (p - u).x();
        };
        ASSERT_FALSE(side(a, b) >= 0 && side(b, c) >= 0 && side(c, a) >= 0)
            << "lit element " << r << ", " << col << " in a triangle";
      }
    }
  }
  for (int r = 0; r < mesh.rows; ++r)
    for (int c = 0; c < mesh.cols; ++c)
      EXPECT_EQ(degree[r * mesh.cols + c] > 0, pattern.tiled(r + mesh.row0, c + mesh.col0) != 0);
  // A module built in code with an absurd offset (module.json refuses it) is refused here too.
  ModuleDescription far = meshed.module;
  far.pattern.offset_px.x() = 1e12;
  EXPECT_THROW(MeshLitElements(far, pattern), InvalidValue);
}

// The mesh's neighbour lists are its triangles' edges, both ways, once each; no two lit
// elements are 8-adjacent, so every neighbour is two or more elements away.
TEST(ElementMesh, NeighboursAreTheTrianglesEdges) {
  const MeshedPattern meshed;
  const ElementMesh& mesh = meshed.mesh;
  const NeighbourLists neighbours = MeshNeighbours(mesh);
  const auto has = [&](int from, int to) {
    const auto [first, last] = neighbours.Of(from);
    return std::count(first, last, to) == 1;
  };
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_TRUE(has(t[k], t[(k + 1) % 3]));
      EXPECT_TRUE(has(t[(k + 1) % 3], t[k]));
    }
  }
  std::size_t edges = 0;
  for (int i = 0; i < mesh.rows * mesh.cols; ++i) {
    const auto [first, last] = neighbours.Of(i);
    edges += last - first;
    for (const int* j = first; j != last; ++j) {
      ASSERT_TRUE(has(*j, i));
      const int dr = std::abs(*j / mesh.cols - i / mesh.cols);
      const int dc = std::abs(*j % mesh.cols - i % mesh.cols);
      EXPECT_GE(std::max(dr, dc), 2);
    }
  }
  std::set<std::pair<int, int>> unique;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k)
      unique.emplace(std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]));
  }
  EXPECT_EQ(edges, 2 * unique.size());
}

// The lit elements of the first 76 × 56 of the mesh's grid as points of `plane`, each at the
// camera pixel (20 + s r, 20 + s c), s = `scale_px` (8: one pattern pitch): the default
// module's projector is turned against the camera, rows along u, columns along v. Points whose
// pixel u lies in (lost_lo, lost_hi) are left out (lost spots).
struct MeshPoints {
  std::vector<Eigen::Vector2i> elements;
  std::vector<Eigen::Vector2d> pixels;
  std::vector<double> depths;
};
MeshPoints PlaneOnMesh(const ElementMesh& mesh, const BinaryArray& pattern,
                       const TiltedPlane& plane, double lost_lo = 0.0, double lost_hi = 0.0,
                       double scale_px = 8.0) {
  EXPECT_GE(mesh.rows, 76);
  EXPECT_GE(mesh.cols, 56);
  MeshPoints out;
  for (int r = 0; r < 76; ++r) {
    for (int c = 0; c < 56; ++c) {
      if (!pattern.tiled(r + mesh.row0, c + mesh.col0)) continue;
      const Eigen::Vector2d px(20.0 + scale_px * r, 20.0 + scale_px * c);
      if (px.x() > lost_lo && px.x() < lost_hi) continue;
      out.elements.emplace_back(r + mesh.row0, c + mesh.col0);
      out.pixels.push_back(px);
      out.depths.push_back(plane.Depth(px));
    }
  }
  return out;
}

// Points of a tilted plane at the lit elements, the camera pixel an affine image of the element
// position: the mesh's map is as exact as the Delaunay one; a lost spot leaves a hole that
// the Delaunay map bridges.
TEST(DepthMap, OnTheElementMeshLostSpotsLeaveHoles) {
  const MeshedPattern meshed;
  const BinaryArray& pattern = meshed.pattern;
  const ElementMesh& mesh = meshed.mesh;
  const TiltedPlane plane;
  const cv::Size size(640, 480);
  const MeshPoints points = PlaneOnMesh(mesh, pattern, plane);
  const std::vector<Eigen::Vector2i>& elements = points.elements;
  const std::vector<Eigen::Vector2d>& pixels = points.pixels;
  const std::vector<double>& depths = points.depths;
  const double max_edge = 5.5 * 8.0;
  const cv::Mat1f full =
      InterpolateDepthOnMesh(size, mesh, elements, pixels, depths, {.max_edge_px = max_edge});
  int filled = 0;
  // Inside the lit elements' hull (the pattern lights one element in six: 6 elements in).
  for (int v = 60; v < 420; ++v) {
    for (int u = 60; u < 580; ++u) {
      ASSERT_FALSE(std::isnan(full(v, u))) << u << ", " << v;
      ASSERT_LE(std::abs(full(v, u) - plane.Depth({u, v})), FloatTolerance(plane.Depth({u, v})));
      ++filled;
    }
  }
  // One spot lost in the middle: the pixels around it empty here, bridged by Delaunay.
  std::size_t lost = 0;
  while ((pixels[lost] - Eigen::Vector2d(320, 240)).norm() > 12.0) ++lost;
  const Eigen::Vector2d hole = pixels[lost];
  auto without = [&](auto v) {
    v.erase(v.begin() + static_cast<std::ptrdiff_t>(lost));
    return v;
  };
  const cv::Mat1f holed = InterpolateDepthOnMesh(size, mesh, without(elements), without(pixels),
                                                 without(depths), {.max_edge_px = max_edge});
  const cv::Mat1f bridged = InterpolateDepth(size, without(pixels), without(depths), max_edge);
  const int u = static_cast<int>(hole.x()), v = static_cast<int>(hole.y());
  EXPECT_TRUE(std::isnan(holed(v, u)));
  EXPECT_FALSE(std::isnan(bridged(v, u)));
  EXPECT_FALSE(std::isnan(holed(v, u + 40)));
  // A point of no triangle (its neighbours within 30 px taken out) gets a disc of the spot
  // radius at its depth; with no triangle filled at all (the point alone), nothing does.
  const std::size_t k = lost + 7;
  std::vector<Eigen::Vector2i> isolated_elements;
  std::vector<Eigen::Vector2d> isolated_pixels;
  std::vector<double> isolated_depths;
  for (std::size_t i = 0; i < elements.size(); ++i) {
    if (i != k && (pixels[i] - pixels[k]).norm() < 30.0) continue;
    isolated_elements.push_back(elements[i]);
    isolated_pixels.push_back(pixels[i]);
    isolated_depths.push_back(depths[i]);
  }
  const cv::Mat1f isolated =
      InterpolateDepthOnMesh(size, mesh, isolated_elements, isolated_pixels, isolated_depths,
                             {.max_edge_px = max_edge, .spot_radius_px = 3.0});
  const cv::Rect around(static_cast<int>(pixels[k].x()) - 5, static_cast<int>(pixels[k].y()) - 5,
                        11, 11);
  const cv::Mat1f near_k = isolated(around);
  EXPECT_EQ(cv::countNonZero(near_k == near_k), 29);  // pixels within 3 px of an integer point
  EXPECT_FLOAT_EQ(isolated(around.y + 5, around.x + 7), static_cast<float>(depths[k]));
  const cv::Mat1f alone =
      InterpolateDepthOnMesh(size, mesh, {elements[k]}, {pixels[k]}, {depths[k]},
                             {.max_edge_px = max_edge, .spot_radius_px = 3.0});
  EXPECT_EQ(cv::countNonZero(alone == alone), 0);
  // A mirror image (a module whose camera sees the projector's elements mirrored): the
  // triangles keep the majority's orientation, and the map is as full.
  std::vector<Eigen::Vector2d> mirrored = pixels;
  for (Eigen::Vector2d& p : mirrored) p.x() = 639.0 - p.x();
  const cv::Mat1f flipped =
      InterpolateDepthOnMesh(size, mesh, elements, mirrored, depths, {.max_edge_px = max_edge});
  int flipped_filled = 0;
  for (int v = 60; v < 420; ++v)
    for (int u = 60; u < 580; ++u) flipped_filled += std::isnan(flipped(v, 639 - u)) ? 0 : 1;
  EXPECT_EQ(flipped_filled, filled);
}

// The wall seen stretched (1.3 pattern pitches per element, as where it is farther or
// oblique): the pattern's sparse places, whose Delaunay edges join elements 5–6 apart, still
// hold their triangles under the 5.5-pitch limit (it grows with the elements' distance past
// 4); with one limit for every edge they leave holes, the same in every frame.
TEST(DepthMap, ThePatternsSparsePlacesHoldWhereTheWallIsSeenStretched) {
  const MeshedPattern meshed;
  const BinaryArray& pattern = meshed.pattern;
  const ElementMesh& mesh = meshed.mesh;
  const TiltedPlane plane;
  const cv::Size size(840, 640);
  const double scale = 1.3 * 8.0;
  const MeshPoints points = PlaneOnMesh(mesh, pattern, plane, 0.0, 0.0, scale);
  const auto empty_inside = [&](double long_edge_elements) {
    const cv::Mat1f map = InterpolateDepthOnMesh(
        size, mesh, points.elements, points.pixels, points.depths,
        {.max_edge_px = 5.5 * 8.0, .long_edge_elements = long_edge_elements});
    int empty = 0;  // inside the lit elements' hull, as in OnTheElementMeshLostSpotsLeaveHoles
    for (int v = 80; v < 540; ++v)
      for (int u = 80; u < 740; ++u) empty += std::isnan(map(v, u)) ? 1 : 0;
    return empty;
  };
  EXPECT_EQ(empty_inside(4.0), 0);
  EXPECT_GT(empty_inside(0.0), 1000);
  std::printf("stretched 1.3: %d pixels empty with one limit for every edge\n", empty_inside(0.0));
}

// A band of lost spots (a joint's gap 40 px wide across the image): holes drawn from the last
// spots seen are too wide by about a triangle on each side; drawn to the midpoints toward the
// lost spots, their mean width over the rows is the band's. The pattern lights one element in
// about six, so the lit spots are ~20 px apart here: a row's width is off by up to ~20 px,
// the mean over 360 rows by a few.
TEST(DepthMap, HolesDrawnToTheMidpointsKeepTheirWidth) {
  const MeshedPattern meshed;
  const BinaryArray& pattern = meshed.pattern;
  const ElementMesh& mesh = meshed.mesh;
  const TiltedPlane plane;
  const cv::Size size(640, 480);
  const double band_lo = 304.0, band_hi = 344.0;  // halfway between element rows
  const MeshPoints points = PlaneOnMesh(mesh, pattern, plane, band_lo, band_hi);
  const auto mean_width = [&](bool midpoints) {
    const cv::Mat1f map =
        InterpolateDepthOnMesh(size, mesh, points.elements, points.pixels, points.depths,
                               {.max_edge_px = 44.0, .holes_to_midpoints = midpoints});
    double sum = 0.0;
    for (int v = 60; v < 420; ++v) {
      int empty = 0;
      for (int u = 240; u < 400; ++u) {
        const float z = map(v, u);
        empty += std::isnan(z) ? 1 : 0;
        // What is drawn lies on the plane, the margins too (extrapolated within it).
        if (!std::isnan(z)) {
          EXPECT_NEAR(z, plane.Depth({u, v}), 1e-3 * plane.Depth({u, v}));
        }
      }
      sum += empty;
    }
    return sum / 360.0;
  };
  const double from_last_seen = mean_width(false), to_midpoints = mean_width(true);
  EXPECT_GT(from_last_seen, band_hi - band_lo + 10.0);
  EXPECT_NEAR(to_midpoints, band_hi - band_lo, 4.0);
  RecordProperty("hole_width_from_last_seen_px", std::to_string(from_last_seen));
  RecordProperty("hole_width_to_midpoints_px", std::to_string(to_midpoints));
}

// Every element lit, on a square grid split into triangles along one diagonal, rows 8 px apart
// in the image; rows 10–14 lost (a hole from v = 92.5 to 132.5, its rims halfway between rows and
// along them). Drawn to the midpoints, the hole keeps its height in every column: each rim
// runs through triangles with an edge on the surface (drawn over their half nearer it) and
// triangles with only a corner on it (drawn at that corner, their part where its weight is at
// least ½); without the corners the rim zigzags and the hole reads 41.5 px (about 1/8 of a
// row too high on each side).
TEST(DepthMap, AHoleAlongARowOfElementsKeepsItsHeight) {
  ElementMesh mesh;
  mesh.rows = 25;
  mesh.cols = 30;
  for (int r = 0; r + 1 < mesh.rows; ++r) {
    for (int c = 0; c + 1 < mesh.cols; ++c) {
      const int a = mesh.Index(r, c), b = mesh.Index(r, c + 1), d = mesh.Index(r + 1, c + 1),
                e = mesh.Index(r + 1, c);
      mesh.triangles.push_back({a, b, d});
      mesh.triangles.push_back({a, d, e});
    }
  }
  const TiltedPlane plane;
  std::vector<Eigen::Vector2i> elements;
  std::vector<Eigen::Vector2d> pixels;
  std::vector<double> depths;
  for (int r = 0; r < mesh.rows; ++r) {
    for (int c = 0; c < mesh.cols; ++c) {
      if (r >= 10 && r <= 14) continue;
      elements.emplace_back(r, c);
      pixels.emplace_back(16.5 + 8.0 * c, 16.5 + 8.0 * r);  // (u, v): rims between pixels
      depths.push_back(plane.Depth(pixels.back()));
    }
  }
  const cv::Mat1f map = InterpolateDepthOnMesh({280, 220}, mesh, elements, pixels, depths,
                                               {.max_edge_px = 20.0, .holes_to_midpoints = true});
  double sum = 0.0;
  int columns = 0;
  for (int u = 40; u < 220; ++u, ++columns) {
    for (int v = 80; v < 152; ++v) sum += std::isnan(map(v, u)) ? 1.0 : 0.0;
  }
  EXPECT_NEAR(sum / columns, 40.0, 0.5);  // pixel centres at integers: ±½ px
  RecordProperty("hole_height_px", std::to_string(sum / columns));
}

// A depth step (a joint's gap 40 px wide across the image, 5 % deeper): the camera sees the
// gap's spots 30 px shifted along the baseline, so the triangles joining them to the wall
// fold on one side and stretch past max_edge_px on the other; all their spots are seen. The
// wall beyond the stretched side ends halfway toward where the gap's first spots would lie
// on it — at the band's edge, not at its own first spots (the margins of session 44 were
// drawn only toward lost spots: such a wall started about half a triangle late).
TEST(DepthMap, AStepsSurfacesAreDrawnToTheMidpoints) {
  const MeshedPattern meshed;
  const double band_lo = 304.0, band_hi = 344.0, shift = 30.0;
  MeshPoints points = PlaneOnMesh(meshed.mesh, meshed.pattern, TiltedPlane{});
  for (std::size_t i = 0; i < points.pixels.size(); ++i) {
    if (points.pixels[i].x() <= band_lo || points.pixels[i].x() >= band_hi) continue;
    points.pixels[i].x() -= shift;
    points.depths[i] *= 1.05;
  }
  const TiltedPlane plane;
  const auto mean_wall_start = [&](bool midpoints) {
    const cv::Mat1f map = InterpolateDepthOnMesh(
        cv::Size(640, 480), meshed.mesh, points.elements, points.pixels, points.depths,
        {.max_edge_px = 44.0, .holes_to_midpoints = midpoints});
    double sum = 0.0;
    for (int v = 60; v < 420; ++v) {
      int u = static_cast<int>(band_hi) - 20;
      while (u < 420 && !(std::abs(map(v, u) - plane.Depth({u, v})) < 1e-3 * plane.Depth({u, v})))
        ++u;
      sum += u;
    }
    return sum / 360.0;
  };
  const double from_first_seen = mean_wall_start(false), to_midpoint = mean_wall_start(true);
  EXPECT_GT(from_first_seen, band_hi + 5.0);
  EXPECT_NEAR(to_midpoint, band_hi, 3.0);
  RecordProperty("wall_start_from_first_seen_px", std::to_string(from_first_seen));
  RecordProperty("wall_start_to_midpoint_px", std::to_string(to_midpoint));
}

}  // namespace
}  // namespace sewer3d
