#include "sewer3d/report/viewer_data.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>

#include "sewer3d/core/check.hpp"
#include "sewer3d/report/html.hpp"

namespace sewer3d {
namespace {

/// Centre of coarse cell `i` in whole-grid cells (a last, partial block is centred on what it
/// holds).
double BlockCentre(int i, int factor, int cells) {
  const int begin = i * factor;
  const int end = std::min(cells, begin + factor);
  return 0.5 * (begin + end);
}

std::string DisplacementBase64(const cv::Mat1f& displacement_mm) {
  std::string bytes;
  bytes.reserve(displacement_mm.total() * 2);
  for (const float d : displacement_mm) {
    const std::int16_t v =
        std::isfinite(d)
            ? static_cast<std::int16_t>(std::clamp(std::lround(d * 100.0F), -32767L, 32767L))
            : static_cast<std::int16_t>(-32768);
    const auto u = static_cast<std::uint16_t>(v);
    bytes += static_cast<char>(u & 0xFFU);
    bytes += static_cast<char>(u >> 8U);
  }
  return html::Base64(bytes);
}

}  // namespace

std::string ViewerDataJson(const PipeModelInfo& info, const CoarseMaps& relief,
                           const CoarseMaps& texture) {
  const MapGrid& grid = info.grid;
  SEWER3D_CHECK(
      relief.region.row0 == 0 && relief.region.rows == grid.rows && relief.region.cols == grid.cols,
      "the viewer's relief must cover the whole grid");
  nlohmann::json j;
  j["radius_mm"] = info.centreline.radius_mm;
  j["rows"] = relief.displacement_mm.rows;
  j["clocks"] = relief.displacement_mm.cols;
  nlohmann::json stations = nlohmann::json::array();
  nlohmann::json frames = nlohmann::json::array();
  for (int i = 0; i < relief.displacement_mm.rows; ++i) {
    const double s =
        grid.station0_mm + BlockCentre(i, relief.row_factor, grid.rows) * grid.resolution_mm;
    stations.push_back(s);
    const AxisFrame f = info.centreline.FrameAt(s);
    for (const Eigen::Vector3d* v : {&f.origin, &f.crown, &f.right}) {
      for (int k = 0; k < 3; ++k) frames.push_back(std::round((*v)[k] * 1e4) / 1e4);
    }
  }
  nlohmann::json clocks = nlohmann::json::array();
  for (int c = 0; c < relief.displacement_mm.cols; ++c)
    clocks.push_back(2.0 * M_PI * BlockCentre(c, relief.col_factor, grid.cols) / grid.cols);
  j["stations_mm"] = stations;
  j["frames"] = frames;
  j["clocks_rad"] = clocks;
  j["displacement_b64"] = DisplacementBase64(relief.displacement_mm);
  j["texture"] = {{"station0_mm", grid.station0_mm},
                  {"station1_mm", grid.station0_mm + texture.texture.rows * texture.row_factor *
                                                         grid.resolution_mm},
                  {"turn_fraction",
                   static_cast<double>(texture.texture.cols * texture.col_factor) / grid.cols}};
  return j.dump();
}

}  // namespace sewer3d
