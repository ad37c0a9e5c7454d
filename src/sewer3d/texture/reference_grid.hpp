#pragma once
/// \file
/// The per-cell statistics of the reference-light estimator (shading.hpp): a grid of log2
/// values of one channel, cell (i, j) at index j · cols + i.

#include <cstdint>
#include <optional>
#include <vector>

namespace sewer3d::reference_grid {

using Grid = std::vector<double>;

/// Harmonic fill of the cells that have no estimate (Gauss–Seidel on the 4-neighbour mean).
void FillHoles(Grid& g, const std::vector<bool>& known, int cols, int rows);

/// Local quadratic regression (Savitzky–Golay) along rows, then along columns: each value is
/// replaced by the quadratic least-squares fit over the 2h + 1 nearest cells (a window shifted
/// inwards at the borders), so that fields quadratic in each coordinate — vignetting, emission
/// fall-off — pass unbiased while cell noise is averaged.
void SmoothQuadratic(Grid& g, int cols, int rows, int half_width);

/// The mean of a histogram's values between its trim and 1 − trim quantiles (bins counted
/// fractionally at the cut; trim 0.5: the median), in bins from the first real bin (bin 0 and
/// the last are the under- and overflow); nullopt when the kept part reaches a censored bin.
/// Unlike the median, the trimmed mean moves continuously when a cell's frames mix two walls.
std::optional<double> TrimmedMeanLog2(const std::uint32_t* histogram, int bins, std::uint64_t total,
                                      double trim);

}  // namespace sewer3d::reference_grid
