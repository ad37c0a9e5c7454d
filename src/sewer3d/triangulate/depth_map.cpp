#include "sewer3d/triangulate/depth_map.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <opencv2/imgproc.hpp>
#include <unordered_map>
#include <utility>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

double SignedArea(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

// Inverse depth interpolated linearly over the pixels inside triangle abc (depths za, zb, zc);
// nothing where an edge is longer than max_edge_px or the triangle has no area (false). With
// max_wc < 1 only the part nearer ab (c's barycentric weight at most max_wc), and with
// only_empty only pixels still empty.
bool FillTriangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                  double za, double zb, double zc, double max_edge_px, cv::Mat1f& depth,
                  double max_wc = 1.0, bool only_empty = false) {
  if ((a - b).norm() > max_edge_px || (b - c).norm() > max_edge_px || (c - a).norm() > max_edge_px)
    return false;
  const double area = SignedArea(a, b, c);
  if (std::abs(area) < 1e-9) return false;
  const int u0 = std::max(0, static_cast<int>(std::ceil(std::min({a.x(), b.x(), c.x()}))));
  const int u1 =
      std::min(depth.cols - 1, static_cast<int>(std::floor(std::max({a.x(), b.x(), c.x()}))));
  const int v0 = std::max(0, static_cast<int>(std::ceil(std::min({a.y(), b.y(), c.y()}))));
  const int v1 =
      std::min(depth.rows - 1, static_cast<int>(std::floor(std::max({a.y(), b.y(), c.y()}))));
  for (int v = v0; v <= v1; ++v) {
    for (int u = u0; u <= u1; ++u) {
      const Eigen::Vector2d p(u, v);
      const double wa = SignedArea(p, b, c) / area;
      const double wb = SignedArea(p, c, a) / area;
      const double wc = 1.0 - wa - wb;
      if (wa < -1e-9 || wb < -1e-9 || wc < -1e-9 || wc > max_wc) continue;
      if (only_empty && !std::isnan(depth(v, u))) continue;
      // Interpolate inverse depth: linear in the image for a plane.
      depth(v, u) = static_cast<float>(1.0 / (wa / za + wb / zb + wc / zc));
    }
  }
  return true;
}

// `z` on the empty pixels within `radius` of `centre`.
void FillDisc(const Eigen::Vector2d& centre, double radius, double z, cv::Mat1f& depth) {
  const int u0 = std::max(0, static_cast<int>(std::ceil(centre.x() - radius)));
  const int u1 = std::min(depth.cols - 1, static_cast<int>(std::floor(centre.x() + radius)));
  const int v0 = std::max(0, static_cast<int>(std::ceil(centre.y() - radius)));
  const int v1 = std::min(depth.rows - 1, static_cast<int>(std::floor(centre.y() + radius)));
  for (int v = v0; v <= v1; ++v) {
    for (int u = u0; u <= u1; ++u) {
      if ((Eigen::Vector2d(u, v) - centre).squaredNorm() > radius * radius) continue;
      if (std::isnan(depth(v, u))) depth(v, u) = static_cast<float>(z);
    }
  }
}

// The grid element (row, column) of mesh grid index k.
Eigen::Vector2d ElementOf(const ElementMesh& mesh, int k) {
  const int row = k / mesh.cols, col = k % mesh.cols;
  return {static_cast<double>(row), static_cast<double>(col)};
}

std::uint64_t EdgeKey(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (hi << 32U) | lo;
}

// The steepest triangle a hole's margin is drawn from: the spread of its corners' depths as
// a fraction of the nearest (a wall seen at 60° from its normal, spots 2 mm apart: ~2 %).
constexpr double kMaxMarginDepthSpan = 0.05;

// Where element c lies in the camera and at what depth by the plane of the filled triangle abd
// (grid ids with points; its inverse depth affine over the image): false where abd is steep
// (a step's flank, a lateral's bore seen end-on: its plane says little about where the surface
// goes on) or too small to reach c (more than three of its heights beyond).
bool Extrapolate(const ElementMesh& mesh, const std::vector<int>& point_of,
                 const std::vector<Eigen::Vector2d>& pixels, const std::vector<double>& depths_mm,
                 const std::array<int, 4>& abdc, Eigen::Vector2d& pixel, double& depth_mm) {
  const auto [a, b, d, c] = abdc;
  const int pa = point_of[a], pb = point_of[b], pd = point_of[d];
  const double lo = std::min({depths_mm[pa], depths_mm[pb], depths_mm[pd]});
  const double hi = std::max({depths_mm[pa], depths_mm[pb], depths_mm[pd]});
  if (hi - lo > kMaxMarginDepthSpan * lo) return false;
  Eigen::Matrix2d elements, image;
  elements << ElementOf(mesh, b) - ElementOf(mesh, a), ElementOf(mesh, d) - ElementOf(mesh, a);
  image << pixels[pb] - pixels[pa], pixels[pd] - pixels[pa];
  if (std::abs(elements.determinant()) < 1e-12) return false;
  pixel = pixels[pa] + image * elements.inverse() * (ElementOf(mesh, c) - ElementOf(mesh, a));
  const double area = SignedArea(pixels[pa], pixels[pb], pixels[pd]);
  if (std::abs(area) < 1e-9) return false;
  const double wa = SignedArea(pixel, pixels[pb], pixels[pd]) / area;
  const double wb = SignedArea(pixel, pixels[pd], pixels[pa]) / area;
  const double wd = 1.0 - wa - wb;
  if (wd < -3.0) return false;
  const double inverse = wa / depths_mm[pa] + wb / depths_mm[pb] + wd / depths_mm[pd];
  if (!(inverse > 0.0)) return false;
  depth_mm = 1.0 / inverse;
  return true;
}

// The margin of the unfilled triangle abc over its half nearer ab, drawn on the plane of the
// filled triangle abd across ab (grid ids; a, b, d with points).
void DrawMargin(const ElementMesh& mesh, const std::vector<int>& point_of,
                const std::vector<Eigen::Vector2d>& pixels, const std::vector<double>& depths_mm,
                double max_edge_px, const std::array<int, 4>& abcd, cv::Mat1f& depth) {
  const auto [a, b, c, d] = abcd;
  Eigen::Vector2d pc;
  double zc = 0.0;
  if (!Extrapolate(mesh, point_of, pixels, depths_mm, {a, b, d, c}, pc, zc)) return;
  FillTriangle(pixels[point_of[a]], pixels[point_of[b]], pc, depths_mm[point_of[a]],
               depths_mm[point_of[b]], zc, max_edge_px, depth, 0.5, true);
}

// The margin of the unfilled triangle bcd at its corner b only (no edge of it on the filled
// surface: b a corner of the filled triangle f, c and d lost), the part where b's weight is at
// least ½, on f's plane. With the edges' margins the surface then ends halfway toward the lost
// spots all along a hole's rim; without it, it ends there only across the triangles that show the
// hole an edge, and 1/8 of a triangle short on average where its rim runs along a row of elements.
void DrawCornerMargin(const ElementMesh& mesh, const std::vector<int>& point_of,
                      const std::vector<Eigen::Vector2d>& pixels,
                      const std::vector<double>& depths_mm, double max_edge_px,
                      const std::array<int, 3>& bcd, const std::array<int, 3>& f,
                      cv::Mat1f& depth) {
  const auto [b, c, d] = bcd;
  // f's other two corners, in f's order after b.
  const int k = f[0] == b ? 0 : f[1] == b ? 1 : 2;
  const int e = f[(k + 1) % 3], g = f[(k + 2) % 3];
  Eigen::Vector2d pc, pd;
  double zc = 0.0, zd = 0.0;
  if (!Extrapolate(mesh, point_of, pixels, depths_mm, {b, e, g, c}, pc, zc) ||
      !Extrapolate(mesh, point_of, pixels, depths_mm, {b, e, g, d}, pd, zd))
    return;
  const Eigen::Vector2d& pb = pixels[point_of[b]];
  const double zb = depths_mm[point_of[b]];
  // Halfway in the image, and in inverse depth (affine over the image on a plane).
  FillTriangle(pb, 0.5 * (pb + pc), 0.5 * (pb + pd), zb, 2.0 / (1.0 / zb + 1.0 / zc),
               2.0 / (1.0 / zb + 1.0 / zd), max_edge_px, depth, 1.0, true);
}

// Each triangle of `mesh` that is not filled — it lost a spot, or its spots straddle a depth
// step (an edge too long, folded) — and shares an edge ab (both spots seen) with a filled
// triangle abd is drawn over the half nearer ab: its third element c's camera pixel is where
// the affine map of abd's elements onto their pixels puts c's element, its inverse depth on
// abd's plane of inverse depth over the image. At a step the surface ends somewhere between
// a, b and c as the projector sees it: c's ray missed it. An unfilled triangle with no such
// edge but a corner on the filled surface is drawn at that corner (DrawCornerMargin).
void FillHoleMargins(const ElementMesh& mesh, const std::vector<int>& point_of,
                     const std::vector<std::array<int, 3>>& filled,
                     const std::vector<Eigen::Vector2d>& pixels,
                     const std::vector<double>& depths_mm, double max_edge_px, cv::Mat1f& depth) {
  // Edge -> the third ids of the filled triangles on it (a mesh edge has at most two);
  // grid id -> a filled triangle with that corner.
  struct Sides {
    std::array<int, 2> third{-1, -1};
    int count = 0;
  };
  std::unordered_map<std::uint64_t, Sides> opposite;
  std::unordered_map<int, int> filled_at;
  opposite.reserve(3 * filled.size());
  for (std::size_t i = 0; i < filled.size(); ++i) {
    const std::array<int, 3>& t = filled[i];
    for (int k = 0; k < 3; ++k) {
      Sides& sides = opposite[EdgeKey(t[k], t[(k + 1) % 3])];
      sides.third[std::min(sides.count, 1)] = t[(k + 2) % 3];
      ++sides.count;
      filled_at.emplace(t[k], static_cast<int>(i));
    }
  }
  for (const std::array<int, 3>& t : mesh.triangles) {
    // t itself filled: a filled triangle on its edge t0 t1 has t2 for its third corner.
    const auto own = opposite.find(EdgeKey(t[0], t[1]));
    if (own != opposite.end() && (own->second.third[0] == t[2] || own->second.third[1] == t[2]))
      continue;
    bool edge_margin = false;
    for (int k = 0; k < 3; ++k) {
      const int a = t[(k + 1) % 3], b = t[(k + 2) % 3], c = t[k];
      if (point_of[a] < 0 || point_of[b] < 0 || point_of[c] == -2) continue;
      const auto it = opposite.find(EdgeKey(a, b));
      // Only where ab has one filled triangle (not t, which is not filled).
      if (it == opposite.end() || it->second.count != 1) continue;
      edge_margin = true;
      DrawMargin(mesh, point_of, pixels, depths_mm, max_edge_px, {a, b, c, it->second.third[0]},
                 depth);
    }
    if (edge_margin) continue;
    for (int k = 0; k < 3; ++k) {
      const int b = t[k], c = t[(k + 1) % 3], d = t[(k + 2) % 3];
      // Toward two lost spots only: a seen one across the triangle (bd over a hole too wide
      // for a filled triangle) is no spot this surface lost.
      if (point_of[b] < 0 || point_of[c] != -1 || point_of[d] != -1) continue;
      const auto f = filled_at.find(b);
      if (f == filled_at.end()) continue;
      DrawCornerMargin(mesh, point_of, pixels, depths_mm, max_edge_px, {b, c, d}, filled[f->second],
                       depth);
    }
  }
}

}  // namespace

cv::Mat1f InterpolateDepth(cv::Size image_size, const std::vector<Eigen::Vector2d>& pixels,
                           const std::vector<double>& depths_mm, double max_edge_px) {
  SEWER3D_CHECK(pixels.size() == depths_mm.size(), "pixels and depths differ in number");
  cv::Mat1f depth(image_size, std::numeric_limits<float>::quiet_NaN());
  if (pixels.size() < 3) return depth;
  cv::Subdiv2D subdiv(cv::Rect(-1, -1, image_size.width + 2, image_size.height + 2));
  std::map<std::pair<float, float>, int> index;  // Subdiv2D returns coordinates, not ids
  for (size_t i = 0; i < pixels.size(); ++i) {
    const cv::Point2f p(static_cast<float>(pixels[i].x()), static_cast<float>(pixels[i].y()));
    if (p.x < 0 || p.y < 0 || p.x > image_size.width - 1 || p.y > image_size.height - 1) continue;
    if (index.emplace(std::make_pair(p.x, p.y), static_cast<int>(i)).second) subdiv.insert(p);
  }
  std::vector<cv::Vec6f> triangles;
  subdiv.getTriangleList(triangles);
  for (const cv::Vec6f& t : triangles) {
    int ids[3];
    bool known = true;
    for (int k = 0; k < 3; ++k) {
      const auto it = index.find({t[2 * k], t[2 * k + 1]});
      if (it == index.end())
        known = false;
      else
        ids[k] = it->second;
    }
    if (!known) continue;  // a triangle touching Subdiv2D's outer virtual vertices
    FillTriangle(pixels[ids[0]], pixels[ids[1]], pixels[ids[2]], depths_mm[ids[0]],
                 depths_mm[ids[1]], depths_mm[ids[2]], max_edge_px, depth);
  }
  return depth;
}

cv::Mat1f InterpolateDepthOnMesh(cv::Size image_size, const ElementMesh& mesh,
                                 const std::vector<Eigen::Vector2i>& elements,
                                 const std::vector<Eigen::Vector2d>& pixels,
                                 const std::vector<double>& depths_mm,
                                 const MeshDepthOptions& options) {
  SEWER3D_CHECK(pixels.size() == depths_mm.size() && pixels.size() == elements.size(),
                "elements, pixels and depths differ in number");
  cv::Mat1f depth(image_size, std::numeric_limits<float>::quiet_NaN());
  // The point of each element of the mesh's grid: −1 none, −2 more than one.
  std::vector<int> point_of(static_cast<size_t>(mesh.rows) * mesh.cols, -1);
  for (size_t i = 0; i < elements.size(); ++i) {
    const int k = mesh.Index(elements[i].x(), elements[i].y());
    if (k >= 0) point_of[k] = point_of[k] == -1 ? static_cast<int>(i) : -2;
  }
  // Triangles with three points (and whether they turn positive in the camera image), and
  // the orientation most of them keep.
  std::vector<std::pair<std::array<int, 3>, bool>> whole;
  int kept_orientation = 0;
  for (const std::array<int, 3>& t : mesh.triangles) {
    const std::array<int, 3> ids{point_of[t[0]], point_of[t[1]], point_of[t[2]]};
    if (ids[0] < 0 || ids[1] < 0 || ids[2] < 0) continue;
    const bool positive = SignedArea(pixels[ids[0]], pixels[ids[1]], pixels[ids[2]]) > 0;
    whole.emplace_back(t, positive);
    kept_orientation += positive ? 1 : -1;
  }
  // The longest camera edge an edge joining elements i and j may have.
  const auto edge_limit_px = [&](int i, int j) {
    const double elements_apart = (elements[i] - elements[j]).cast<double>().norm();
    return options.long_edge_elements > 0.0
               ? options.max_edge_px * std::max(1.0, elements_apart / options.long_edge_elements)
               : options.max_edge_px;
  };
  std::vector<char> in_triangle(pixels.size(), 0);
  std::vector<std::array<int, 3>> filled;
  for (const auto& [t, positive] : whole) {
    if (positive != (kept_orientation > 0)) continue;
    const int a = point_of[t[0]], b = point_of[t[1]], c = point_of[t[2]];
    if ((pixels[a] - pixels[b]).norm() > edge_limit_px(a, b) ||
        (pixels[b] - pixels[c]).norm() > edge_limit_px(b, c) ||
        (pixels[c] - pixels[a]).norm() > edge_limit_px(c, a))
      continue;
    if (!FillTriangle(pixels[a], pixels[b], pixels[c], depths_mm[a], depths_mm[b], depths_mm[c],
                      std::numeric_limits<double>::infinity(), depth))
      continue;
    for (const int i : {a, b, c}) in_triangle[i] = 1;
    filled.push_back(t);
  }
  // Discs complete a mesh; without a single triangle (an edge limit below the spot spacing)
  // the map stays empty, as the Delaunay map does.
  if (filled.empty()) return depth;
  if (options.holes_to_midpoints)
    FillHoleMargins(mesh, point_of, filled, pixels, depths_mm, options.max_edge_px, depth);
  for (size_t i = 0; i < pixels.size(); ++i)
    if (!in_triangle[i]) FillDisc(pixels[i], options.spot_radius_px, depths_mm[i], depth);
  return depth;
}

int CountDepthPixels(const cv::Mat1f& depth_mm) {
  int count = 0;
  for (int r = 0; r < depth_mm.rows; ++r) {
    const float* row = depth_mm[r];
    for (int c = 0; c < depth_mm.cols; ++c) count += std::isnan(row[c]) ? 0 : 1;
  }
  return count;
}

}  // namespace sewer3d
