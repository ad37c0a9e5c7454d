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

/// Buffers kept between frames: a 5 MP label image is 20 MB, and allocating it afresh costs
/// more page faults than the labelling itself.
struct SpotWorkspace {
  cv::Mat1i labels;
  cv::Mat stats, centroids;
};

/// Finds spots in `image` (8- or 16-bit grey) from its foreground `mask` and local mean.
/// Weights are I − mean over the component's bounding box grown by one pixel.
std::vector<Spot> DetectSpots(const cv::Mat& image, const cv::Mat1b& mask,
                              const cv::Mat1f& local_mean, const SpotOptions& options,
                              SpotWorkspace* workspace = nullptr);

}  // namespace sewer3d
