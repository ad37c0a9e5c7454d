// Block means with sums, so tiles can arrive in any order and each whole-grid cell counts once.

#include "sewer3d/report/map_downsample.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sewer3d/core/check.hpp"

namespace sewer3d {

int DownsampleFactor(int cells, int max_cells) {
  SEWER3D_CHECK(max_cells > 0, "max_cells must be positive");
  return std::max(1, (cells + max_cells - 1) / max_cells);
}

MapDownsampler::MapDownsampler(const MapCrop& region, int grid_cols, int row_factor, int col_factor)
    : grid_cols_(grid_cols) {
  SEWER3D_CHECK(region.rows > 0 && region.cols > 0 && grid_cols > 0, "empty region");
  SEWER3D_CHECK(row_factor >= 1 && col_factor >= 1, "factors must be at least 1");
  out_.region = region;
  out_.row_factor = row_factor;
  out_.col_factor = col_factor;
  const cv::Size size((region.cols + col_factor - 1) / col_factor,
                      (region.rows + row_factor - 1) / row_factor);
  colour_sum_ = cv::Mat3f(size, cv::Vec3f(0, 0, 0));
  colour_n_ = cv::Mat1f::zeros(size);
  displacement_sum_ = cv::Mat1f::zeros(size);
  displacement_n_ = cv::Mat1f::zeros(size);
  cells_ = cv::Mat1f::zeros(size);
}

void MapDownsampler::Add(const PipeMaps& maps, int first_row) {
  const MapCrop& g = out_.region;
  const int begin = std::max(g.row0, first_row);
  const int end = std::min(g.row0 + g.rows, first_row + maps.texture.rows);
  const int first_col = (g.col0 % grid_cols_ + grid_cols_) % grid_cols_;
  for (int row = begin; row < end; ++row) {
    const int r = row - first_row;
    const int out_row = (row - g.row0) / out_.row_factor;
    const cv::Vec3b* texture = maps.texture[r];
    const float* displacement = maps.displacement_mm[r];
    const std::uint8_t* coverage = maps.coverage[r];
    int col = first_col;  // walks the region's columns, wrapping at the grid's last
    for (int c = 0; c < g.cols; ++c, col = col + 1 == grid_cols_ ? 0 : col + 1) {
      const int out_col = c / out_.col_factor;
      cells_(out_row, out_col) += 1.0F;
      if (coverage[col] != static_cast<std::uint8_t>(Coverage::kNone)) {
        const cv::Vec3b bgr = texture[col];
        colour_sum_(out_row, out_col) += cv::Vec3f(bgr[0], bgr[1], bgr[2]);
        colour_n_(out_row, out_col) += 1.0F;
      }
      const float d = displacement[col];
      if (std::isfinite(d)) {
        displacement_sum_(out_row, out_col) += d;
        displacement_n_(out_row, out_col) += 1.0F;
      }
    }
  }
}

CoarseMaps MapDownsampler::Finish() const {
  CoarseMaps out = out_;
  const cv::Size size = cells_.size();
  out.texture = cv::Mat3b(size, cv::Vec3b(0, 0, 0));
  out.displacement_mm = cv::Mat1f(size, std::numeric_limits<float>::quiet_NaN());
  out.coverage = cv::Mat1f::zeros(size);
  for (int i = 0; i < size.height; ++i) {
    for (int j = 0; j < size.width; ++j) {
      if (colour_n_(i, j) > 0.0F) {
        const cv::Vec3f mean = colour_sum_(i, j) / colour_n_(i, j);
        out.texture(i, j) = cv::Vec3b(cv::saturate_cast<std::uint8_t>(mean[0]),
                                      cv::saturate_cast<std::uint8_t>(mean[1]),
                                      cv::saturate_cast<std::uint8_t>(mean[2]));
      }
      if (displacement_n_(i, j) > 0.0F)
        out.displacement_mm(i, j) = displacement_sum_(i, j) / displacement_n_(i, j);
      if (cells_(i, j) > 0.0F) out.coverage(i, j) = colour_n_(i, j) / cells_(i, j);
    }
  }
  return out;
}

void DownsampleModelMaps(const std::filesystem::path& model_dir, const PipeModelInfo& info,
                         std::vector<MapDownsampler*> downsamplers) {
  auto feed = [&](const PipeMaps& maps, int first_row) {
    for (MapDownsampler* d : downsamplers) d->Add(maps, first_row);
  };
  if (info.whole_maps) {
    feed(ReadMapFiles(WholeMapFiles(model_dir), info.grid), 0);
    return;
  }
  for (const ModelTile& t : info.tiles)
    feed(ReadMapFiles(TileMapFiles(model_dir, t.index), info.grid.Tile(t.row0, t.rows)), t.row0);
}

}  // namespace sewer3d
