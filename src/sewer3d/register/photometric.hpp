#pragma once
/// \file
/// The photometric term of the projection registration (projection_registration.hpp, issue 15
/// item 4): where a wall has texture that gives SIFT no keypoints — the glaze streaks and mottle
/// of vitrified clay, bands rather than corners — the corrected textures of the two
/// acquisitions still say how far b lies along the pipe. Each sampled point of b carries its
/// texture intensity I_b; moved by the pose and projected into a's camera it meets a's intensity,
///   r = I_a(π(R p + t)) − (α I_b + β),
/// with the gain and offset (α, β) of the two views' brightness fitted in closed form. The
/// residual's gradient is ∇I_a · ∂π/∂p · [I, −[R p]×], the same form as the point-to-plane
/// row with the normal replaced by m = (∂π/∂p)ᵀ ∇I_a.
///
/// A cylinder leaves the geometry blind along its axis and about it, and the odometry's guess
/// can be a centimetre off there (a slipping cable counter), far outside the photometric
/// term's basin (about the texture's scale, 1–2 mm). So the weak directions of the geometry
/// are first searched on a grid for the best normalised cross-correlation of the two textures
/// (blurred to the grid's step); the term is used only when that peak is clear — high, and
/// higher than any other peak of the grid — which a featureless wall (plastic) never gives.

#include <opencv2/core.hpp>
#include <vector>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/register/information.hpp"

namespace sewer3d {

struct PhotometricOptions {
  bool enabled = true;   ///< false: the geometry alone (the paper's projection registration)
  double blur_px = 1.0;  ///< Gaussian σ of the textures before the gradients
  /// The textures less their Gaussian mean over this σ (mm on the wall): what the RGB-D stage's
  /// shading correction leaves differs between two views at scales of the light's fall-off,
  /// and a smooth texture (plastic's faint clouds) would pull the pose toward that difference.
  double highpass_mm = 6.0;
  /// Search of the geometry's weak directions: ± this far (mm; rotation as arc at the scene's
  /// distance) on a grid of search_step_mm, then ± one step on a grid four times finer.
  double search_range_mm = 16.0;
  double search_step_mm = 2.0;
  int search_sample_step_px = 8;  ///< every n-th pixel of b for the search's correlation
  int max_search_directions = 2;  ///< the weakest eigenvectors searched (a cylinder has two)
  /// The search's peak is clear when its correlation reaches min_ncc and exceeds every grid
  /// point farther than one step from it by min_ncc_margin.
  double min_ncc = 0.5;
  double min_ncc_margin = 0.1;
  int min_samples = 200;  ///< samples of b that land in a with texture, for the term to count

  void Check() const;
};

/// A residual row of a Gauss–Newton step in the convention of information.hpp.
struct ResidualRow {
  Eigen::Matrix<double, 1, 6> j;  ///< ∂r/∂δ
  double r = 0.0;
};

/// A texture's grey level (0–1) and its Gaussian mean over highpass_px, made once per image.
struct GreyTexture {
  cv::Mat1f level, mean;
};
GreyTexture MakeGreyTexture(const cv::Mat3b& color_bgr, double highpass_px);
/// The texture as the term reads it: the grey level blurred by blur_px (Gaussian σ) less the
/// mean.
cv::Mat1f TextureIntensity(const GreyTexture& grey, double blur_px);
/// That intensity with its derivatives along columns and rows (per pixel).
struct TextureMaps {
  cv::Mat1f intensity, du, dv;
};
TextureMaps MakeTextureMaps(const GreyTexture& grey, double blur_px);

/// A point of b (camera frame, mm) with b's intensity where it was seen.
struct TextureSample {
  Eigen::Vector3d point;
  double intensity = 0.0;
};
/// Samples of b's points whose pixel has an intensity in `intensity_b`.
std::vector<TextureSample> SampleTexture(const std::vector<Eigen::Vector3d>& points_b,
                                         const CameraModel& camera_b, const cv::Mat1f& intensity_b);

/// Photometric rows at a pose, brightness gain and offset fitted to them first (both returned).
struct PhotometricRows {
  std::vector<ResidualRow> rows;
  double gain = 1.0, offset = 0.0;
};
PhotometricRows AssociatePhotometric(const TextureMaps& a, const CameraModel& camera_a,
                                     const std::vector<TextureSample>& b, const Rigid3d& pose);

/// Normalised cross-correlation of b's intensities with a's at a pose, over the samples of b
/// that land in a's image.
struct TextureCorrelation {
  int samples = 0;
  double ncc = 0.0;  ///< 0 when the intensities do not vary
};
TextureCorrelation CorrelateTextures(const cv::Mat1f& intensity_a, const CameraModel& camera_a,
                                     const std::vector<TextureSample>& b, const Rigid3d& pose);

struct TextureSearchResult {
  bool clear = false;  ///< the peak is clear (PhotometricOptions::min_ncc, min_ncc_margin)
  Rigid3d pose;        ///< at the peak (the start where not clear)
  int overlap = 0;     ///< samples of coarse_b that land in a at the start
  /// At the start (fine maps), at the coarse peak (refined on the fine maps where clear), and
  /// the best coarse grid point farther than one step from the peak.
  double ncc_start = 0.0, ncc_peak = 0.0, ncc_other = 0.0;
  /// The peak is a ridge (textures streaked along one direction): only the sharp direction was
  /// moved along, and shift_mm.x() is along it.
  bool ridge = false;
  Vector6d along_ridge = Vector6d::Zero();  ///< the ridge's direction, as `directions` are
  Eigen::Vector2d shift_mm = Eigen::Vector2d::Zero();  ///< along the directions searched
};

/// Searches a grid along `directions` (updates δ per mm of the (mm, L·rad) metric, at most two)
/// from `start`: coarse on `coarse_a`/`coarse_b`, then finer on `fine_a`/`fine_b`. Where the
/// coarse peak is a ridge, it must stand clear of everything off the ridge, and only the
/// direction across it is refined and moved along.
struct TextureSearchInput {
  const cv::Mat1f& coarse_a;
  const std::vector<TextureSample>& coarse_b;
  const cv::Mat1f& fine_a;
  const std::vector<TextureSample>& fine_b;
};
TextureSearchResult SearchTexture(const TextureSearchInput& in, const CameraModel& camera_a,
                                  const Rigid3d& start, const std::vector<Vector6d>& directions,
                                  const PhotometricOptions& options);

}  // namespace sewer3d
