#pragma once
/// \file
/// The picture of each observation for WS/inspection/crops/ (texture above the displacement
/// view, at most max_side_px on its long side), made in one pass over the model's pieces in
/// station order. A crop is begun at the first piece that reaches it and handed out as soon as
/// a piece ends past its last row, so memory holds only the crops open at the current piece,
/// each already downsampled — not every crop of a 100 m run at full resolution.

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "sewer3d/inspect/observation.hpp"
#include "sewer3d/model/pipe_map.hpp"
#include "sewer3d/report/map_downsample.hpp"

namespace sewer3d {

class InspectionCrops {
 public:
  using Done = std::function<void(std::size_t index, const cv::Mat3b& image)>;

  /// `boxes` (one per observation) on the whole-run `grid`; rows outside it are clipped.
  InspectionCrops(const std::vector<MapCrop>& boxes, const MapGrid& grid, double view_range_mm,
                  int max_side_px);
  /// A piece of the maps (its grid a tile of the run's); pieces come in station order. Calls
  /// `done` for each crop the piece completes.
  void Add(const PipeMaps& piece, const Done& done);
  /// Hands out every crop not yet handed out (one no piece reached shows no data).
  void Finish(const Done& done);

 private:
  void Open(std::size_t i);
  void Close(std::size_t i, const Done& done);

  MapGrid grid_;
  double range_mm_;
  int max_side_px_;
  std::vector<MapCrop> boxes_;  ///< clipped to the grid's rows, at least one cell
  std::vector<std::optional<MapDownsampler>> open_;
  std::vector<bool> handed_out_;
};

}  // namespace sewer3d
