#pragma once
/// \file
/// A spot looked for where one is expected: at the camera pixel the lattice of a frame's
/// points predicts for a lit element that gave none. Finds spots too faint for the binariser
/// (a dark patch, a black wall at a grey wall's exposure) by averaging and by knowing where
/// to look.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>

namespace sewer3d {

struct FaintSpotOptions {
  /// A spot is there when the brightest 3 x 3 mean within the inner disk exceeds the
  /// background (median of the ring around it) by this many standard deviations of a 3 x 3
  /// mean of the ring's noise (its MAD-scaled spread over 3)...
  double min_sigmas = 6.0;
  /// ...and by at least this many 8-bit grey levels (NiblackBinariser::LevelScale).
  double min_levels = 1.0;
  /// The noise assumed at least (8-bit levels): a clean 8-bit image's ring is a few values
  /// and its MAD may be 0.
  double min_noise_levels = 0.5;
  void Check() const;
};

struct FaintSpot {
  Eigen::Vector2d centre_px;  ///< weighted centroid (pixel centres at integers)
  double contrast = 0.0;      ///< peak 3 x 3 mean over the background, 8-bit levels
  double noise = 0.0;         ///< the ring's standard deviation, 8-bit levels
};

/// Looks for a spot centred within `inner_px` of `at` in a grey image (8- or 16-bit, with
/// `level_scale` of its values per 8-bit grey level: NiblackBinariser::LevelScale): the
/// background is measured on the ring inner_px < d <= outer_px (which must hold no other
/// spot), the spot's centre is the centroid of the pixels' excess over it within inner_px of
/// the brightest 3 x 3 mean. None where the ring leaves the image, or nothing stands out.
std::optional<FaintSpot> FaintSpotAt(const cv::Mat& image, double level_scale,
                                     const Eigen::Vector2d& at, double inner_px, double outer_px,
                                     const FaintSpotOptions& options = {});

}  // namespace sewer3d
