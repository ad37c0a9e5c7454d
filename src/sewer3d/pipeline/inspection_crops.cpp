#include "sewer3d/pipeline/inspection_crops.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "sewer3d/io/model_io.hpp"

namespace sewer3d {
namespace {

MapCrop Clipped(const MapCrop& box, const MapGrid& grid) {
  MapCrop c = box;
  c.row0 = std::clamp(box.row0, 0, std::max(0, grid.rows - 1));
  const int end = std::clamp(box.row0 + box.rows, c.row0 + 1, std::max(c.row0 + 1, grid.rows));
  c.rows = end - c.row0;
  c.cols = std::clamp(box.cols, 1, std::max(1, grid.cols));
  return c;
}

}  // namespace

InspectionCrops::InspectionCrops(const std::vector<MapCrop>& boxes, const MapGrid& grid,
                                 double view_range_mm, int max_side_px)
    : grid_(grid),
      range_mm_(view_range_mm),
      max_side_px_(max_side_px),
      open_(boxes.size()),
      handed_out_(boxes.size(), false) {
  for (const MapCrop& b : boxes) boxes_.push_back(Clipped(b, grid));
}

void InspectionCrops::Open(std::size_t i) {
  if (open_[i]) return;
  const MapCrop& b = boxes_[i];
  // Texture above displacement: the picture is twice the crop's rows high. Block means down to
  // less than twice the size, the rest by area resampling on the picture.
  const int f = std::max(1, std::max(2 * b.rows, b.cols) / max_side_px_);
  open_[i].emplace(b, grid_.cols, f, f);
}

void InspectionCrops::Close(std::size_t i, const Done& done) {
  Open(i);
  const CoarseMaps c = open_[i]->Finish();
  open_[i].reset();
  handed_out_[i] = true;
  cv::Mat3b both;
  cv::vconcat(c.texture, DisplacementView(c.displacement_mm, range_mm_), both);
  const double scale =
      std::min(1.0, static_cast<double>(max_side_px_) / std::max(both.rows, both.cols));
  if (scale < 1.0) cv::resize(both, both, cv::Size(), scale, scale, cv::INTER_AREA);
  done(i, both);
}

void InspectionCrops::Add(const PipeMaps& piece, const Done& done) {
  const int first = static_cast<int>(
      std::lround((piece.grid.station0_mm - grid_.station0_mm) / grid_.resolution_mm));
  const int end = first + piece.grid.rows;
  for (std::size_t i = 0; i < boxes_.size(); ++i) {
    const MapCrop& b = boxes_[i];
    if (handed_out_[i] || b.row0 >= end || b.row0 + b.rows <= first) continue;
    Open(i);
    open_[i]->Add(piece, first);
    if (b.row0 + b.rows <= end) Close(i, done);
  }
}

void InspectionCrops::Finish(const Done& done) {
  for (std::size_t i = 0; i < boxes_.size(); ++i) {
    if (!handed_out_[i]) Close(i, done);
  }
}

}  // namespace sewer3d
