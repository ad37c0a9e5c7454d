#pragma once
/// \file
/// Pinhole camera with 3-term radial Brown–Conrady distortion (OpenCV's model with zero
/// tangential terms). Used for cameras and, as an inverse camera, for projectors.
///
/// Model (DESIGN.md, module contract): for a point (X, Y, Z) in the camera frame,
///   x = X / Z, y = Y / Z, r² = x² + y²,
///   x_d = x (1 + k1 r² + k2 r⁴ + k3 r⁶), y_d likewise,
///   u = fx x_d + cx, v = fy y_d + cy   (pixel centres at integer coordinates).
/// The radial map r ↦ r_d = r (1 + k1 r² + k2 r⁴ + k3 r⁶) is only invertible on its first
/// increasing branch [0, r_fold): beyond the fold two different rays land on the same pixel.
/// Project and Unproject refuse points outside that branch instead of returning garbage.

#include <Eigen/Core>
#include <array>
#include <limits>
#include <optional>

namespace sewer3d {

/// Image size and intrinsic parameters (pixels) of a camera or projector.
struct CameraIntrinsics {
  /// Largest image side accepted (any camera or projector is far below).
  static constexpr int kMaxImageSide = 1 << 15;
  int width = 0;                           ///< image width, px
  int height = 0;                          ///< image height, px
  double fx = 0.0, fy = 0.0;               ///< focal lengths, px
  double cx = 0.0, cy = 0.0;               ///< principal point, px (pixel centres at integers)
  std::array<double, 3> k{0.0, 0.0, 0.0};  ///< radial k1, k2, k3

  /// Throws std::invalid_argument unless sizes and focal lengths are positive and finite.
  void Check() const;
};

/// Camera projection and its inverse. Cheap to copy; immutable after construction.
class CameraModel {
 public:
  /// Checks the intrinsics and locates the fold of the radial polynomial.
  explicit CameraModel(const CameraIntrinsics& intrinsics);

  const CameraIntrinsics& intrinsics() const { return intrinsics_; }

  /// Undistorted radius where the radial map stops increasing (+inf if it never does).
  double fold_radius() const { return fold_radius_; }
  /// Distorted radius reached at the fold: the largest invertible distorted radius.
  double fold_radius_distorted() const { return fold_radius_distorted_; }

  /// Radial map applied to normalised coordinates (no validity check).
  Eigen::Vector2d Distort(const Eigen::Vector2d& normalized) const;
  /// Inverse radial map; nullopt where the distorted radius lies beyond the fold.
  std::optional<Eigen::Vector2d> Undistort(const Eigen::Vector2d& distorted) const;

  /// Pixel of a point in the camera frame (mm). nullopt if Z <= 0 or the ray lies beyond the
  /// fold of the distortion polynomial. The pixel may lie outside the image.
  std::optional<Eigen::Vector2d> Project(const Eigen::Vector3d& p_in_camera) const;
  /// Normalised undistorted coordinates (x, y) at Z = 1 of a pixel; nullopt beyond the fold.
  std::optional<Eigen::Vector2d> Unproject(const Eigen::Vector2d& pixel) const;
  /// Unit direction (camera frame) of the ray through a pixel; nullopt beyond the fold.
  std::optional<Eigen::Vector3d> Ray(const Eigen::Vector2d& pixel) const;

  /// Pixel ↔ distorted normalised coordinates.
  Eigen::Vector2d PixelToDistorted(const Eigen::Vector2d& pixel) const;
  Eigen::Vector2d DistortedToPixel(const Eigen::Vector2d& distorted) const;

  /// True when every pixel of the image (its outer corners included) can be unprojected.
  bool WholeImageInvertible() const;

 private:
  double RadialFactor(double r2) const;

  CameraIntrinsics intrinsics_;
  double fold_radius_ = std::numeric_limits<double>::infinity();
  double fold_radius_distorted_ = std::numeric_limits<double>::infinity();
};

}  // namespace sewer3d
