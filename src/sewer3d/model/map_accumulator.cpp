#include "sewer3d/model/map_accumulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "sewer3d/core/check.hpp"
#include "sewer3d/model/map_fill.hpp"
#include "sewer3d/model/unroll.hpp"

namespace sewer3d {

void MapAccumulatorOptions::Check() const {
  ValidateNotNegative("splat_radius_mm", splat_radius_mm);
  ValidateNotNegative("max_hole_mm", max_hole_mm);
  ValidateNotNegative("hole_edge_band_mm", hole_edge_band_mm);
}

double DepthWeight(double depth_mm, double sigma_ref_mm, double depth_ref_mm) {
  ValidatePositive("sigma_ref_mm", sigma_ref_mm);
  ValidatePositive("depth_ref_mm", depth_ref_mm);
  const double sigma = sigma_ref_mm * std::pow(depth_mm / depth_ref_mm, 2);
  return 1.0 / (sigma * sigma);
}

double BorderFeather(double u_px, double v_px, int width, int height, double ramp_px) {
  ValidatePositive("ramp_px", ramp_px);
  // Pixel centres at integers: the border lies half a pixel beyond the first and last.
  const double border = std::min({u_px + 0.5, v_px + 0.5, width - 0.5 - u_px, height - 0.5 - v_px});
  return std::clamp(border / ramp_px, 1e-3, 1.0);
}

MapAccumulator::MapAccumulator(const Centreline& centreline, const MapGrid& tile,
                               const MapAccumulatorOptions& options)
    : centreline_(centreline), tile_(tile), options_(options) {
  options.Check();
  ValidatePositive("resolution_mm", tile.resolution_mm);
  SEWER3D_VALIDATE(tile.rows > 0 && tile.cols > 0, "tile",
                   "needs rows and columns, got " << tile.rows << " x " << tile.cols);
  SEWER3D_CHECK(centreline.points.size() >= 2);
  // The margin holds every cell a hole that reaches into the tile can span, its neighbours
  // the fill reads, and the cells a splat of a point beyond the tile reaches.
  // The edge trimming reads frames and holes within twice its band.
  halo_ = static_cast<int>(std::ceil(
              (options.max_hole_mm + options.splat_radius_mm + 2.0 * options.hole_edge_band_mm) /
              tile.resolution_mm)) +
          2;
  ext_ = tile;
  ext_.station0_mm = tile.station0_mm - halo_ * tile.resolution_mm;
  ext_.rows = tile.rows + 2 * halo_;
  sum_w_ = cv::Mat1f::zeros(ext_.rows, ext_.cols);
  sum_wd_ = cv::Mat1f::zeros(ext_.rows, ext_.cols);
  sum_wc_ = cv::Mat3f::zeros(ext_.rows, ext_.cols);
  count_ = cv::Mat1w::zeros(ext_.rows, ext_.cols);
  if (options.hole_edge_band_mm > 0.0) {
    last_frame_ = cv::Mat1i::zeros(ext_.rows, ext_.cols);
    frames_ = cv::Mat1b::zeros(ext_.rows, ext_.cols);
    seen_ = cv::Mat1b::zeros(ext_.rows, ext_.cols);
  }
  station_guess_mm_ = tile.station0_mm;
}

std::size_t MapAccumulator::MemoryBytes() const {
  return static_cast<std::size_t>(ext_.rows) * static_cast<std::size_t>(ext_.cols) * kBytesPerCell;
}

void MapAccumulator::MarkFrame(int row, int col, bool measured) {
  int& last = last_frame_(row, col);
  if (last >= 2 * frame_ + (measured ? 1 : 0)) return;  // already counted for this frame
  if (last < 2 * frame_) seen_(row, col) = cv::saturate_cast<unsigned char>(seen_(row, col) + 1);
  if (measured) frames_(row, col) = cv::saturate_cast<unsigned char>(frames_(row, col) + 1);
  last = 2 * frame_ + (measured ? 1 : 0);
}

void MapAccumulator::AddToCell(int row, int col, double weight, double displacement_mm,
                               const cv::Vec3f& bgr) {
  sum_w_(row, col) += static_cast<float>(weight);
  sum_wd_(row, col) += static_cast<float>(weight * displacement_mm);
  sum_wc_(row, col) += static_cast<float>(weight) * bgr;
  if (!frames_.empty()) MarkFrame(row, col, true);
}

template <typename Visit>
bool MapAccumulator::VisitCells(const Eigen::Vector3d& p_model, Visit&& visit, Landing* landing) {
  // Points far outside the tile are rejected from a first-order station (one frame, no
  // iterations): a caller feeds whole acquisitions to every tile they may reach. Its error is
  // ~ Δs² / bend radius, far below the 10 mm slack for any pipe bend.
  const AxisFrame near = centreline_.FrameAt(station_guess_mm_);
  const double approx = station_guess_mm_ + (p_model - near.origin).dot(near.tangent);
  const double slack = options_.splat_radius_mm + 10.0;
  if (approx < ext_.station0_mm - slack ||
      approx > ext_.station0_mm + ext_.rows * ext_.resolution_mm + slack)
    return false;
  const CylPoint cyl = Unroll(centreline_, p_model, station_guess_mm_);
  station_guess_mm_ = cyl.station_mm;
  const double res = ext_.resolution_mm;
  const double row_f = (cyl.station_mm - ext_.station0_mm) / res;  // cell edges at integers
  const double col_f = cyl.clock_rad / (2.0 * std::numbers::pi) * ext_.cols;
  const double reach = options_.splat_radius_mm / res;
  if (row_f + reach < 0.0 || row_f - reach >= ext_.rows) return false;
  const int row = static_cast<int>(std::floor(row_f));
  const int col = std::min(static_cast<int>(col_f), ext_.cols - 1);
  *landing = {cyl.radius_mm - centreline_.radius_mm, row, col};
  if (options_.splat_radius_mm <= 0.0) {
    if (row >= 0 && row < ext_.rows) visit(row, col, 1.0);
    return true;
  }
  // Kernel (1 − d²/r²)² over the cells whose centres lie within r (columns wrap).
  const double col_mm = 2.0 * std::numbers::pi * centreline_.radius_mm / ext_.cols;
  const double r2 = options_.splat_radius_mm * options_.splat_radius_mm;
  const int r_lo = std::max(0, static_cast<int>(std::floor(row_f - reach - 0.5)));
  const int r_hi = std::min(ext_.rows - 1, static_cast<int>(std::ceil(row_f + reach - 0.5)));
  const int c_reach = static_cast<int>(std::ceil(options_.splat_radius_mm / col_mm)) + 1;
  for (int r = r_lo; r <= r_hi; ++r) {
    const double dr = (r + 0.5 - row_f) * res;
    for (int k = col - c_reach; k <= col + c_reach; ++k) {
      const double dc = (k + 0.5 - col_f) * col_mm;
      const double d2 = dr * dr + dc * dc;
      if (d2 >= r2) continue;
      visit(r, ((k % ext_.cols) + ext_.cols) % ext_.cols, (1.0 - d2 / r2) * (1.0 - d2 / r2));
    }
  }
  return true;
}

bool MapAccumulator::Add(const Eigen::Vector3d& p_model, const cv::Vec3f& bgr, double weight) {
  SEWER3D_CHECK(weight > 0.0 && std::isfinite(weight), "weight = " << weight);
  Landing at;
  const auto add = [&](int r, int c, double kernel) {
    AddToCell(r, c, weight * kernel, at.displacement_mm, bgr);
  };
  if (!VisitCells(p_model, add, &at)) return false;
  if (at.row >= 0 && at.row < ext_.rows) {
    count_(at.row, at.col) =
        static_cast<std::uint16_t>(std::min<int>(count_(at.row, at.col) + 1, 65535));
  }
  return true;
}

bool MapAccumulator::AddSeen(const Eigen::Vector3d& p_model) {
  if (!CountsFrames()) return false;
  Landing at;
  return VisitCells(
      p_model, [&](int r, int c, double /*kernel*/) { MarkFrame(r, c, false); }, &at);
}

PipeMaps MapAccumulator::Finish() const {
  cv::Mat1f displacement(ext_.rows, ext_.cols, std::numeric_limits<float>::quiet_NaN());
  cv::Mat3f colour = cv::Mat3f::zeros(ext_.rows, ext_.cols);
  cv::Mat1b coverage = cv::Mat1b::zeros(ext_.rows, ext_.cols);
  for (int r = 0; r < ext_.rows; ++r) {
    for (int c = 0; c < ext_.cols; ++c) {
      const float w = sum_w_(r, c);
      if (!(w > 0.0f)) continue;
      displacement(r, c) = sum_wd_(r, c) / w;
      colour(r, c) = sum_wc_(r, c) / w;
      coverage(r, c) = static_cast<unsigned char>(Coverage::kMeasured);
    }
  }
  const double col_mm = 2.0 * std::numbers::pi * centreline_.radius_mm / ext_.cols;
  if (!frames_.empty()) {
    const double cell_mm = std::max(ext_.resolution_mm, col_mm);
    TrimHoleEdges(static_cast<int>(std::lround(options_.hole_edge_band_mm / cell_mm)), frames_,
                  seen_, displacement, colour, coverage);
  }
  const int max_rows =
      static_cast<int>(std::floor(options_.max_hole_mm / ext_.resolution_mm + 1e-9));
  const int max_cols = static_cast<int>(std::floor(options_.max_hole_mm / col_mm + 1e-9));
  if (max_rows > 0 && max_cols > 0)
    FillSmallHoles(max_rows, max_cols, displacement, colour, coverage);
  const cv::Range rows(halo_, halo_ + tile_.rows), all = cv::Range::all();
  PipeMaps maps;
  maps.grid = tile_;
  maps.displacement_mm = displacement(rows, all).clone();
  colour(rows, all).convertTo(maps.texture, CV_8UC3);  // rounds and saturates
  maps.samples = count_(rows, all).clone();
  maps.coverage = coverage(rows, all).clone();
  return maps;
}

}  // namespace sewer3d
