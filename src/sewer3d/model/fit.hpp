#pragma once
/// \file
/// Least-squares plane and cylinder fits for accuracy evaluation (paper Tables 1 and 2): fit
/// the surface to the points, then report the residual distances.

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace sewer3d {

struct PlaneFit {
  Eigen::Vector3d normal;  ///< unit; points toward the camera (normal.z() < 0)
  double offset = 0.0;     ///< plane: normal · x + offset = 0
  double rms_mm = 0.0;     ///< of the orthogonal distances
  double max_mm = 0.0;
};

/// Total least squares (SVD of the centred points). Needs >= 3 non-collinear points.
std::optional<PlaneFit> FitPlane(const std::vector<Eigen::Vector3d>& points);

/// Signed distance (mm) of a point from the plane, positive on the far side from the camera.
double SignedDistance(const PlaneFit& plane, const Eigen::Vector3d& point);

struct CylinderFit {
  Eigen::Vector3d axis_point;      ///< point on the axis closest to the camera centre
  Eigen::Vector3d axis_direction;  ///< unit
  double radius_mm = 0.0;
  double rms_mm = 0.0;  ///< of |distance to axis − radius|
  double max_mm = 0.0;
  bool converged = false;
  /// A plane fits the points at least as well (plane_rms_mm ≤ rms_mm): a flat cloud "fits" a
  /// cylinder of any large radius, so the radius measures nothing.
  bool flat = false;
  double plane_rms_mm = 0.0;  ///< of the total-least-squares plane (FitPlane)
};

/// Signed distance (mm) of a point from the cylinder, positive outside (away from the axis).
double SignedDistance(const CylinderFit& cylinder, const Eigen::Vector3d& point);

/// Geometric fit (Ceres, Levenberg–Marquardt) of distance-to-axis − r, started from an
/// algebraic circle fit in the plane perpendicular to `axis_guess`; `flat` tells a cloud with
/// no curvature to measure.
std::optional<CylinderFit> FitCylinder(const std::vector<Eigen::Vector3d>& points,
                                       const Eigen::Vector3d& axis_guess);

/// FitCylinder started from each coordinate axis (y first, the rig's pipe axis): the converged
/// fit of least RMS. A patch of a pipe seen along another axis otherwise converges to a small
/// cylinder through part of it.
std::optional<CylinderFit> FitCylinderAnyAxis(const std::vector<Eigen::Vector3d>& points);

/// The points in front of the camera (z > 0) whose viewing directions (x/z, y/z) lie in the
/// central `fraction` of the cloud's extent along both image axes (the paper evaluates an inner
/// part of the image); with `fraction` 1 every point in front of the camera.
std::vector<Eigen::Vector3d> InnerPoints(const std::vector<Eigen::Vector3d>& points,
                                         double fraction);

}  // namespace sewer3d
