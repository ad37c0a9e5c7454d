#pragma once
/// \file
/// The displacement map at inspection scale: block means of the model's map over cells of
/// about 1 mm (docs/inspection.md). Joints, connections, spalling, deposits and deformation are
/// all larger than that, so the search runs here: a 10 m run of DN300 is ~9 M coarse cells
/// (38 MB), built tile by tile from a run's map tiles, so memory stays bounded.

#include <opencv2/core/mat.hpp>

#include "sewer3d/model/pipe_map.hpp"

namespace sewer3d {

struct CoarseMap {
  MapGrid fine;    ///< the model's whole-run grid
  int factor = 5;  ///< fine cells per coarse cell along both axes
  /// Mean displacement (mm, positive outward) over each block's covered cells; NaN where the
  /// block has less than half of its cells covered. Rows = ceil(fine.rows / factor), cols =
  /// ceil(fine.cols / factor) (the last column block may be narrower).
  cv::Mat1f displacement_mm;
  cv::Mat1f measured;  ///< share of each block's cells with a displacement, 0..1
  /// The texture's grey level (luminance, 1..255) averaged over finer blocks of `grey_factor`
  /// cells, for thin dark lines (cracks, texture_cracks.hpp); 0 where less than half of a
  /// block has texture. Empty when the builder was asked for none or the maps had no texture.
  cv::Mat1b grey;
  int grey_factor = 2;

  [[nodiscard]] double GreyRowMm() const { return grey_factor * fine.resolution_mm; }
  [[nodiscard]] double GreyColMm(double radius_mm) const;   ///< arc of a grey column block
  [[nodiscard]] double GreyRowStationMm(double row) const;  ///< at a fractional grey row
  [[nodiscard]] double GreyColClockRad(double col) const;   ///< at a fractional grey column

  [[nodiscard]] double RowMm() const { return factor * fine.resolution_mm; }
  [[nodiscard]] double RowStationMm(int row) const;       ///< centre of the block's fine rows
  [[nodiscard]] double ColClockRad(int col) const;        ///< centre of the block's fine columns
  [[nodiscard]] double ColArcMm(double radius_mm) const;  ///< width of a full column block
  [[nodiscard]] int FineRow(int coarse_row) const { return coarse_row * factor; }
  [[nodiscard]] int FineCol(int coarse_col) const { return coarse_col * factor; }
};

/// Builds a CoarseMap from the tiles of a run's maps (or from its whole maps), in any order;
/// tile boundaries need not fall on block boundaries.
class CoarseMapBuilder {
 public:
  /// Blocks of factor = max(1, round(cell_mm / fine.resolution_mm)) cells; with grey_cell_mm >
  /// 0 also the grey map, over blocks of about grey_cell_mm (1 … 15 cells).
  CoarseMapBuilder(const MapGrid& fine, double cell_mm, double grey_cell_mm = 0.0);
  /// Adds `tile` (rows of the whole grid from `tile.grid.station0_mm`); its texture (where its
  /// coverage has a cell) to the grey map when the tile has one.
  void Add(const PipeMaps& tile);
  /// The block means: NaN where less than half of a block's cells are covered.
  [[nodiscard]] CoarseMap Finish() const;

 private:
  static constexpr int kMaxGreyFactor = 15;  ///< 225 cells × 255 fit the uint16 sums
  void AddGrey(const PipeMaps& tile, int first_row);
  [[nodiscard]] cv::Mat1b GreyMeans() const;

  CoarseMap map_;
  cv::Mat1d sum_;
  cv::Mat1i count_;
  cv::Mat1w grey_sum_;  ///< sums of grey levels (≤ 225 cells × 255)
  cv::Mat1b grey_count_;
  bool has_grey_ = false;
};

}  // namespace sewer3d
