#pragma once
/// \file
/// Coarse copies of the pipe model's maps for the report: a region of the whole-run grid
/// (`MapCrop`, columns wrapping around the clock) averaged over blocks of row_factor × col_factor
/// cells. Fed one tile at a time (`Add`), so a run kept only as tiles is downsampled with memory
/// for one tile plus the coarse sums.

#include <filesystem>
#include <vector>

#include "sewer3d/inspect/observation.hpp"
#include "sewer3d/io/model_io.hpp"
#include "sewer3d/model/pipe_map.hpp"

namespace sewer3d {

/// A coarse map: cell (i, j) averages whole-grid rows region.row0 + i·row_factor … and
/// columns region.col0 + j·col_factor … (mod the grid's columns).
struct CoarseMaps {
  MapCrop region;
  int row_factor = 1;
  int col_factor = 1;
  cv::Mat3b texture;          ///< BGR mean of covered cells; black where none is covered
  cv::Mat1f displacement_mm;  ///< mean of the cells with a displacement; NaN where none
  cv::Mat1f coverage;         ///< share of cells covered (measured or filled), 0..1
};

/// The smallest factor ≥ 1 that brings `cells` down to at most `max_cells`.
int DownsampleFactor(int cells, int max_cells);

class MapDownsampler {
 public:
  /// `region` of a grid with `grid_cols` columns; factors ≥ 1; region non-empty.
  MapDownsampler(const MapCrop& region, int grid_cols, int row_factor, int col_factor);
  /// Adds the cells of `maps` (its rows are whole-grid rows first_row …) that fall in the region.
  void Add(const PipeMaps& maps, int first_row);
  [[nodiscard]] CoarseMaps Finish() const;

 private:
  CoarseMaps out_;
  int grid_cols_;
  cv::Mat3f colour_sum_;
  cv::Mat1f colour_n_, displacement_sum_, displacement_n_, cells_;
};

/// Feeds every downsampler with the maps of the model in `model_dir` (described by `info`):
/// the whole-run files when they exist, else one tile at a time. FileError when a map file is
/// missing or malformed.
void DownsampleModelMaps(const std::filesystem::path& model_dir, const PipeModelInfo& info,
                         std::vector<MapDownsampler*> downsamplers);

}  // namespace sewer3d
