#include "sewer3d/triangulate/element_mesh.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace sewer3d {

ElementMesh MeshLitElements(const ModuleDescription& module, const BinaryArray& pattern) {
  const PatternLayout& layout = module.pattern;
  // Inverse of ElementCentre: the elements whose centres lie on the projector image.
  const auto first = [&](double offset) {
    return static_cast<int>(std::ceil((-0.5 - offset + 0.5) / layout.pitch_px - 0.5));
  };
  const auto last = [&](double offset, int size) {
    return static_cast<int>(std::floor((size - 0.5 - offset + 0.5) / layout.pitch_px - 0.5));
  };
  ElementMesh mesh;
  mesh.col0 = first(layout.offset_px.x());
  mesh.row0 = first(layout.offset_px.y());
  mesh.cols = last(layout.offset_px.x(), module.projector.width) - mesh.col0 + 1;
  mesh.rows = last(layout.offset_px.y(), module.projector.height) - mesh.row0 + 1;
  if (mesh.rows <= 0 || mesh.cols <= 0) return mesh;
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

}  // namespace sewer3d
