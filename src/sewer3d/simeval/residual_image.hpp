#pragma once
/// \file
/// A frame's residuals as a picture, as the paper shows its accuracy captures: every point
/// where the camera sees it, coloured by its signed distance from a surface (the fitted one,
/// or the true one), so that what is systematic (a bowl, a tilt, the image's corners bent by
/// the lens) stands apart from what is noise.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "sewer3d/sim/scene.hpp"

namespace sewer3d {

struct ResidualImageOptions {
  int width_px = 800;     ///< of the drawn view (the picture adds margins for text)
  double range_mm = 0.0;  ///< colours saturate at ±range_mm; 0: ResidualRange of the residuals
  std::string title;      ///< drawn above the view
  /// 0: each point's own residual. n > 0: each point drawn with the mean residual of the
  /// points in its cell of an n-across grid over the view (square cells), so that a
  /// systematic pattern (a tilt, a bowl, the corners) shows through the spots' own noise.
  int smoothing_cells = 0;
};

/// A round colour range for residuals: the smallest of 0.05, 0.1, 0.2, 0.5, 1, 2, 5, … mm that
/// is at least three times their RMS (finite values only; 0.05 mm when there are none).
double ResidualRange(const std::vector<double>& residual_mm);

/// Signed distance (mm) of each camera-frame point from the true surface along its ray,
/// positive beyond the surface (farther from the camera); NaN where the ray misses it.
std::vector<double> RayResiduals(const Scene& scene, const std::vector<Eigen::Vector3d>& points);

/// The points drawn at their viewing directions (x/z, y/z, scaled to the cloud's extent; image
/// x to the right, y down as in the camera), each a disc of about the points' spacing coloured
/// by its residual (DisplacementView: negative blue, 0 white, positive red; NaN left out),
/// with a colour bar, the title and the RMS of the residuals. `points` and `residual_mm` are
/// parallel; points behind the camera are left out. BGR.
cv::Mat3b ResidualImage(const std::vector<Eigen::Vector3d>& points,
                        const std::vector<double>& residual_mm,
                        const ResidualImageOptions& options = {});

/// A picture and the file name it is written under.
struct NamedPicture {
  std::string file;
  cv::Mat3b image;
};

/// The pictures of `evaluate plane|cylinder --out`: residuals.png (`fitted_mm`, each point's
/// signed distance from the fitted surface, titled `fitted_title`) and residuals_smoothed.png
/// (the same over cells of about 50 points: the systematic part, the spots' noise averaged);
/// with `truth`, truth_residuals.png and truth_residuals_smoothed.png (RayResiduals).
std::vector<NamedPicture> ResidualPictures(const std::vector<Eigen::Vector3d>& points,
                                           const std::vector<double>& fitted_mm,
                                           const std::string& fitted_title, const Scene* truth);

}  // namespace sewer3d
