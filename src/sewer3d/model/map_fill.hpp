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

}  // namespace sewer3d
