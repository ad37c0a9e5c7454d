#include "sewer3d/triangulate/element_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "sewer3d/core/check.hpp"

namespace sewer3d {
namespace {

// The most elements a projector can hold at a pitch of 1 px (the least module.json accepts)
// on the largest image read (kMaxCameraPixels, 2^26); the default module has 78 k.
constexpr double kMaxMeshElements = 67108864.0;

}  // namespace

ElementMesh MeshLitElements(const ModuleDescription& module, const BinaryArray& pattern) {
  const PatternLayout& layout = module.pattern;
  // Inverse of ElementCentre: the elements whose centres lie on the projector image.
  const double pitch = layout.pitch_px;
  const double c_first = std::ceil(-layout.offset_px.x() / pitch - 0.5);
  const double r_first = std::ceil(-layout.offset_px.y() / pitch - 0.5);
  const double cols =
      std::floor((module.projector.width - layout.offset_px.x()) / pitch - 0.5) - c_first + 1.0;
  const double rows =
      std::floor((module.projector.height - layout.offset_px.y()) / pitch - 0.5) - r_first + 1.0;
  ElementMesh mesh;
  if (!(rows > 0.0 && cols > 0.0)) return mesh;  // no element centre on the projector
  SEWER3D_VALIDATE(
      rows * cols <= kMaxMeshElements && std::abs(c_first) < 1e9 && std::abs(r_first) < 1e9,
      "pattern.pitch_px",
      pitch << " px with offset_px (" << layout.offset_px.transpose() << ") lays a grid of "
            << rows * cols << " elements from column " << c_first << ", row " << r_first
            << " over the " << module.projector.width << " x " << module.projector.height
            << " px projector (at most " << kMaxMeshElements << ", within ±1e9)");
  mesh.col0 = static_cast<int>(c_first);
  mesh.row0 = static_cast<int>(r_first);
  mesh.cols = static_cast<int>(cols);
  mesh.rows = static_cast<int>(rows);
  // Element coordinates are integers: Subdiv2D gives its vertices back exactly.
  cv::Subdiv2D subdiv(cv::Rect(mesh.col0 - 1, mesh.row0 - 1, mesh.cols + 2, mesh.rows + 2));
  int lit = 0;
  for (int r = mesh.row0; r < mesh.row0 + mesh.rows; ++r) {
    for (int c = mesh.col0; c < mesh.col0 + mesh.cols; ++c) {
      if (!pattern.tiled(r, c)) continue;
      subdiv.insert(cv::Point2f(static_cast<float>(c), static_cast<float>(r)));
      ++lit;
    }
  }
  if (lit < 3) return mesh;
  std::vector<cv::Vec6f> list;
  subdiv.getTriangleList(list);
  mesh.triangles.reserve(list.size());
  for (const cv::Vec6f& t : list) {
    std::array<int, 3> ids{};
    bool inside = true;
    for (int k = 0; k < 3 && inside; ++k) {
      ids[k] = mesh.Index(static_cast<int>(std::lround(t[2 * k + 1])),
                          static_cast<int>(std::lround(t[2 * k])));
      inside = ids[k] >= 0;  // not one of Subdiv2D's outer virtual vertices
    }
    if (!inside) continue;
    const double area = (t[2] - t[0]) * (t[5] - t[1]) - (t[3] - t[1]) * (t[4] - t[0]);
    if (area == 0.0) continue;
    if (area < 0.0) std::swap(ids[1], ids[2]);
    mesh.triangles.push_back(ids);
  }
  return mesh;
}

NeighbourLists MeshNeighbours(const ElementMesh& mesh) {
  const std::size_t cells = static_cast<std::size_t>(mesh.rows) * mesh.cols;
  std::vector<std::pair<int, int>> edges;
  edges.reserve(6 * mesh.triangles.size());
  for (const std::array<int, 3>& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      edges.emplace_back(t[k], t[(k + 1) % 3]);
      edges.emplace_back(t[(k + 1) % 3], t[k]);
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  NeighbourLists out;
  out.offsets.assign(cells + 1, 0);
  out.indices.reserve(edges.size());
  for (const auto& [from, to] : edges) {
    ++out.offsets[from + 1];
    out.indices.push_back(to);
  }
  for (std::size_t i = 1; i <= cells; ++i) out.offsets[i] += out.offsets[i - 1];
  return out;
}

}  // namespace sewer3d
