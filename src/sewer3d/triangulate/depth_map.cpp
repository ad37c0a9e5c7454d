#include "sewer3d/triangulate/depth_map.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <opencv2/imgproc.hpp>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

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
    const Eigen::Vector2d &a = pixels[ids[0]], &b = pixels[ids[1]], &c = pixels[ids[2]];
    if ((a - b).norm() > max_edge_px || (b - c).norm() > max_edge_px ||
        (c - a).norm() > max_edge_px)
      continue;
    const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    if (std::abs(area) < 1e-9) continue;
    const int u0 = std::max(0, static_cast<int>(std::ceil(std::min({a.x(), b.x(), c.x()}))));
    const int u1 = std::min(image_size.width - 1,
                            static_cast<int>(std::floor(std::max({a.x(), b.x(), c.x()}))));
    const int v0 = std::max(0, static_cast<int>(std::ceil(std::min({a.y(), b.y(), c.y()}))));
    const int v1 = std::min(image_size.height - 1,
                            static_cast<int>(std::floor(std::max({a.y(), b.y(), c.y()}))));
    for (int v = v0; v <= v1; ++v) {
      for (int u = u0; u <= u1; ++u) {
        const Eigen::Vector2d p(u, v);
        const double wa = ((b - p).x() * (c - p).y() - (b - p).y() * (c - p).x()) / area;
        const double wb = ((c - p).x() * (a - p).y() - (c - p).y() * (a - p).x()) / area;
        const double wc = 1.0 - wa - wb;
        if (wa < -1e-9 || wb < -1e-9 || wc < -1e-9) continue;
        // Interpolate inverse depth: linear in the image for a plane.
        const double inv = wa / depths_mm[ids[0]] + wb / depths_mm[ids[1]] + wc / depths_mm[ids[2]];
        depth(v, u) = static_cast<float>(1.0 / inv);
      }
    }
  }
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
