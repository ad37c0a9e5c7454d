#include "sewer3d/triangulate/depth_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

double SignedArea(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

// Inverse depth interpolated linearly over the pixels inside triangle abc (depths za, zb, zc);
// nothing where an edge is longer than max_edge_px or the triangle has no area (false).
bool FillTriangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                  double za, double zb, double zc, double max_edge_px, cv::Mat1f& depth) {
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
      if (wa < -1e-9 || wb < -1e-9 || wc < -1e-9) continue;
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
                                 const std::vector<double>& depths_mm, double max_edge_px,
                                 double spot_radius_px) {
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
    whole.emplace_back(ids, positive);
    kept_orientation += positive ? 1 : -1;
  }
  std::vector<char> in_triangle(pixels.size(), 0);
  bool any_triangle = false;
  for (const auto& [ids, positive] : whole) {
    if (positive != (kept_orientation > 0)) continue;
    if (!FillTriangle(pixels[ids[0]], pixels[ids[1]], pixels[ids[2]], depths_mm[ids[0]],
                      depths_mm[ids[1]], depths_mm[ids[2]], max_edge_px, depth))
      continue;
    for (const int i : ids) in_triangle[i] = 1;
    any_triangle = true;
  }
  // Discs complete a mesh; without a single triangle (an edge limit below the spot spacing)
  // the map stays empty, as the Delaunay map does.
  if (!any_triangle) return depth;
  for (size_t i = 0; i < pixels.size(); ++i)
    if (!in_triangle[i]) FillDisc(pixels[i], spot_radius_px, depths_mm[i], depth);
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
