#pragma once
/// \file
/// Each module's range offset, estimated where neighbouring modules see the same wall (the
/// seams). A module's calibration error makes its depth maps read the wall a little too far
/// or too near (a disparity offset: about 0.05–0.1 mm at 150 mm for the errors a calibration
/// leaves); where two modules overlap, the wall they see is the same, so the difference of
/// their radii there is the difference of their offsets (times the cosine of each ray's
/// incidence). Over the ring of modules the differences give every offset but their common
/// part (a diameter error, which no overlap can see): the estimate has zero sum.

#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace sewer3d {

/// A wall sample of one module in the pipe's cylindrical coordinates.
struct ModuleWallSample {
  int module = 0;
  double station_mm = 0.0;
  double clock_rad = 0.0;
  double radius_mm = 0.0;
  double cos_incidence = 1.0;  ///< |ray · wall normal|: how much of a range offset is radial
};

struct ModuleOffsetOptions {
  double cell_mm = 10.0;           ///< samples are compared per cell of this side on the wall
  int min_cell_samples = 2;        ///< of each module in a cell
  double max_difference_mm = 1.0;  ///< cells whose modules differ more (steps, edges) are left out
  int min_cells = 20;              ///< a pair of modules needs this many shared cells
  double max_offset_mm = 1.0;      ///< an offset beyond this is not a calibration's: none applied
  void Check() const;
};

struct ModuleOffsets {
  bool estimated = false;        ///< false: offsets all zero (why says why)
  std::string why;               ///< when not estimated
  std::vector<double> range_mm;  ///< per module: subtract this along each ray
  std::vector<int> pair_cells;   ///< per module m: cells shared with module m + 1 (ring)
  int cells = 0;                 ///< cells compared
  double rms_before_mm = 0.0;    ///< weighted RMS of the radius differences in the cells
  double rms_after_mm = 0.0;     ///< the same with the offsets taken out
};

/// Collects wall samples into the cells (memory: the cells' sums, not the samples), then
/// estimates the offsets.
class ModuleOffsetEstimator {
 public:
  /// `modules` modules 0 … modules − 1, neighbours in a ring; `radius_mm` the model radius
  /// (sets the cells' width in clock).
  ModuleOffsetEstimator(int modules, double radius_mm, const ModuleOffsetOptions& options);
  void Add(const ModuleWallSample& sample);
  /// As EstimateModuleOffsets below.
  [[nodiscard]] ModuleOffsets Estimate() const;

 private:
  struct Sums {
    double radius = 0.0, cosine = 0.0;
    int n = 0;
  };
  int modules_;
  double radius_mm_;
  ModuleOffsetOptions options_;
  std::int64_t clock_cells_;
  std::unordered_map<std::int64_t, std::size_t> index_;  // cell → its first module's sums
  std::vector<Sums> sums_;                               // modules_ per cell
};

/// The offsets of `modules` modules (0 … modules − 1, neighbours in a ring) from their samples,
/// `radius_mm` the model radius (sets the cells' width in clock). Two passes: a weighted least
/// squares over every cell's pairwise differences with a zero-sum constraint, then again
/// without the cells beyond three robust sigmas of the first fit. Not estimated (all zero)
/// where a pair of neighbours shares fewer than min_cells cells or an offset exceeds
/// max_offset_mm.
ModuleOffsets EstimateModuleOffsets(const std::vector<ModuleWallSample>& samples, int modules,
                                    double radius_mm, const ModuleOffsetOptions& options);

}  // namespace sewer3d
