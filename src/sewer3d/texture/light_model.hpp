#pragma once
/// \file
/// A smooth model of a module's reference light over its image (texture/shading.hpp): the ring
/// light's emission pattern, its colour change with the emission angle and the lens's
/// per-channel shading all vary slowly over the image, so per channel log2 R is fitted by a
/// low-degree 2-D polynomial in the cell centres' positions. Wall content that the per-cell
/// medians of a short or mixed run keep (the median of a cell flips between two materials from
/// one cell to the next) cannot follow a smooth polynomial and is averaged out; a robust fit
/// (Huber, iteratively reweighted) keeps outlying cells from pulling it.

#include <vector>

namespace sewer3d {

/// Fits the polynomial of total degree `degree` (1 ≤ degree ≤ 6) in x, y ∈ [−1, 1] (cell
/// centres over the grid) to the `known` cells of `grid` (cols × rows, row-major, log2 values)
/// and replaces every cell by the fit. Returns the RMS of the known cells' residuals (log2) or
/// a negative value when there are fewer known cells than terms (the grid is then left alone).
double FitSmoothLight(std::vector<double>& grid, const std::vector<bool>& known, int cols, int rows,
                      int degree, double huber_log2 = 0.1);

}  // namespace sewer3d
