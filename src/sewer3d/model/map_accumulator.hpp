#pragma once
/// \file
/// Texture and displacement maps (paper §4.4): every point is unrolled about the centreline
/// (unroll.hpp) and lands in a cell of the regular (station, clock) grid, which keeps the
/// weighted mean radius and colour and the number of samples. Seams between modules blend by
/// the weighted mean; small holes are filled by interpolation (Coverage::kFilled), large ones
/// stay empty. One accumulator holds one tile of rows, so memory stays bounded on long runs;
/// the tiles of a grid (MapGrid::Tile) put side by side equal one accumulator over the whole.
///
/// Density: a map cell (0.2 mm) is much finer than the spacing of a module's triangulated
/// points (1–3 mm), so the caller should feed dense per-pixel samples — each valid pixel of an
/// RGB-D acquisition's depth map unprojected to 3D with its corrected colour (pixels at
/// ~150 mm are ~0.06 mm apart) — and nearest-cell splatting (splat_radius_mm = 0) gives the
/// paper's per-cell means. For sparse clouds, splat_radius_mm > 0 spreads each point over the
/// cells within that radius with weight (1 − d²/r²)² (choose r ≈ the point spacing).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "sewer3d/model/pipe_map.hpp"

namespace sewer3d {

struct MapAccumulatorOptions {
  double splat_radius_mm = 0.0;  ///< 0: each point to its nearest cell; else kernel radius
  double max_hole_mm = 2.0;      ///< holes at most this long and wide are filled
  /// Hole edges at the frames' median (TrimHoleEdges, before the small holes are filled):
  /// covered cells this close to a hole that fewer than half of the frames seeing them
  /// measured are dropped. 0: off (a hole's edge is the farthest any frame reached). Frames
  /// are counted per cell between BeginFrame calls; a frame sees the cells it measured and
  /// those it marked with AddSeen (its own holes).
  double hole_edge_band_mm = 0.0;
  void Check() const;
};

/// The weight of a point triangulated at depth `depth_mm`: 1/σ² with σ = sigma_ref_mm ·
/// (depth_mm / depth_ref_mm)² (the depth error of triangulation grows with depth squared).
double DepthWeight(double depth_mm, double sigma_ref_mm, double depth_ref_mm);

/// A factor in (0, 1] feathering a pixel's weight toward its image's border: distance to the
/// nearest border / ramp_px, clamped to [0.001, 1]; blends module seams without steps.
double BorderFeather(double u_px, double v_px, int width, int height, double ramp_px);

class MapAccumulator {
 public:
  /// Accumulates the rows of `tile` (a grid over the centreline's stations); `centreline` is
  /// referenced and must outlive the accumulator. Throws InvalidValue for bad options or an
  /// empty tile.
  MapAccumulator(const Centreline& centreline, const MapGrid& tile,
                 const MapAccumulatorOptions& options);

  /// Adds a point of the model frame with its colour (BGR, 0–255 scale, float) and weight
  /// (> 0; e.g. DepthWeight × BorderFeather). Returns false (and adds nothing) when it lands
  /// beyond the tile and its margin. Consecutive neighbouring points unroll fastest.
  bool Add(const Eigen::Vector3d& p_model, const cv::Vec3f& bgr, double weight);

  /// Marks the cells a point of the frame's view would reach as seen by the frame, without
  /// measuring them: where the frame has a hole (hole_edge_band_mm; no effect without it).
  /// Returns false when the point lands beyond the tile and its margin.
  bool AddSeen(const Eigen::Vector3d& p_model);

  /// Starts the next frame's points (for hole_edge_band_mm, which counts the frames per cell).
  void BeginFrame() { ++frame_; }
  /// Whether frames are counted (hole_edge_band_mm > 0), i.e. AddSeen has an effect.
  [[nodiscard]] bool CountsFrames() const { return !seen_.empty(); }

  /// The tile's maps: means per cell, holes ≤ max_hole_mm filled and flagged.
  [[nodiscard]] PipeMaps Finish() const;

  /// Memory of the sums per cell (bytes); the tile plus its margin rows are held.
  static constexpr std::size_t kBytesPerCell =
      5 * sizeof(float) + sizeof(std::uint16_t) + sizeof(std::int32_t) + 2 * sizeof(std::uint8_t);
  [[nodiscard]] std::size_t MemoryBytes() const;

 private:
  struct Landing {
    double displacement_mm = 0.0;
    int row = 0, col = 0;  ///< the point's own cell of the extended grid (row may lie outside)
  };
  /// Calls visit(row, col, kernel weight) for the cells of the extended grid `p_model`
  /// reaches (its own cell, or the splat's) after the displacement is in `landing`. False
  /// (nothing visited) when it lands beyond the tile and its margin.
  template <typename Visit>
  bool VisitCells(const Eigen::Vector3d& p_model, Visit&& visit, Landing* landing);
  void AddToCell(int row, int col, double weight, double displacement_mm, const cv::Vec3f& bgr);
  void MarkFrame(int row, int col, bool measured);

  const Centreline& centreline_;
  MapGrid tile_;
  MapGrid ext_;  // the tile and its margin: halo_ rows on both sides
  MapAccumulatorOptions options_;
  int halo_ = 0;
  double station_guess_mm_ = 0.0;
  cv::Mat1f sum_w_, sum_wd_;
  cv::Mat3f sum_wc_;
  cv::Mat1w count_;
  cv::Mat1i last_frame_;  // 2 × the frame that last saw the cell, + 1 where it measured it
  cv::Mat1b frames_;      // frames that measured the cell (to 255)
  cv::Mat1b seen_;        // frames that measured the cell or marked it seen (to 255)
  int frame_ = 1;
};

}  // namespace sewer3d
