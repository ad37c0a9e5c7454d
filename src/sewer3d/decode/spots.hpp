#pragma once
/// \file
/// Spot centres with sub-pixel precision: connected components of the Niblack mask, filtered
/// by size, each centred by its contrast-weighted centroid.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace sewer3d {

struct Spot {
  Eigen::Vector2d centre_px;  ///< camera pixel, pixel centres at integers
  int area_px = 0;            ///< pixels in the mask component
  double contrast = 0.0;      ///< peak of I − local mean
};

struct SpotOptions {
  int min_area_px = 3;
  int max_area_px = 400;
  /// Components whose bounding box is more elongated than this are rejected (merged spots,
  /// crack edges).
  double max_aspect = 3.0;
  void Check() const;
};

/// Buffers kept between frames (runs of the mask, their components).
struct SpotWorkspace {
  struct Run {
    int v, u0, u1;  ///< row, first and last column
    int parent;     ///< union-find link
  };
  std::vector<Run> runs;
  std::vector<int> row_start;  ///< first run of each row (rows + 1 entries)
  std::vector<int> members;    ///< run indices grouped by component
  std::vector<int> component;  ///< per run: its component's index
};

/// Finds spots from a foreground `mask` and the contrast image `excess` (NiblackBinariser::
/// excess(): scaled max(0, I − local mean)): 8-connected components of the mask, found as
/// runs joined by union-find (no label image). The centre is the centroid weighted by the
/// excess over the component's bounding box grown by one pixel, without the pixels of other
/// components.
std::vector<Spot> DetectSpots(const cv::Mat1b& mask, const cv::Mat1w& excess,
                              const SpotOptions& options, SpotWorkspace* workspace = nullptr);

}  // namespace sewer3d
