#pragma once
/// \file
/// Filling the small holes of a map (map_accumulator.hpp).

#include <opencv2/core/mat.hpp>

namespace sewer3d {

/// Fills each hole (4-connected cells with coverage kNone; columns wrap around the clock) that
/// spans at most `max_rows` rows and `max_cols` columns and does not touch the first or last
/// row: each of its cells gets the inverse-distance mean of the nearest covered cell in each of
/// the four grid directions (exact for a field linear in station and clock), in
/// `displacement_mm` and `colour`, and coverage kFilled. Larger holes stay as they are.
void FillSmallHoles(int max_rows, int max_cols, cv::Mat1f& displacement_mm, cv::Mat3f& colour,
                    cv::Mat1b& coverage);

/// A hole's edge where most frames put it, not where the one reaching farthest does: each
/// covered cell within `band` cells of an uncovered one is kept where more than half of the
/// frames that see it (`seen`: measured it, or have a hole there) measured it (`frames`) —
/// but no more than the most that measured a cell within `band` cells (a surface only a few
/// frames measure, such as a connection's rim, stays) —, uncovered (coverage kNone, displacement
/// NaN, colour 0) where fewer did, and on a tie kept only where it lies nearer a kept cell than an
/// uncovered one (halfway between two frames' edges). Columns wrap around the clock. With every
/// frame's surface drawn to the midpoints toward its lost spots (unbiased for one frame), the union
/// of the frames' surfaces makes holes too narrow; this puts their edges at the frames' median.
void TrimHoleEdges(int band, const cv::Mat1b& frames, const cv::Mat1b& seen,
                   cv::Mat1f& displacement_mm, cv::Mat3f& colour, cv::Mat1b& coverage);

}  // namespace sewer3d
