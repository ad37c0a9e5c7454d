#pragma once
/// \file
/// Linear (DLT) triangulation of a camera–projector correspondence (Hartley & Zisserman,
/// 2nd ed., §12.2, p. 312), in normalised coordinates (distortion already removed).

#include <Eigen/Core>
#include <optional>

#include "sewer3d/core/rigid3.hpp"

namespace sewer3d {

/// The point X (camera frame, mm) seen at normalised camera coordinates `camera_xy` and
/// normalised projector coordinates `projector_xy`, with P_camera = [I | 0] and
/// P_projector = [R | t] = projector_from_camera. Solves A X = 0 (four rows, x × (P X) = 0)
/// for the right singular vector of its smallest singular value. nullopt when the rays are
/// parallel or the point lies behind either centre.
std::optional<Eigen::Vector3d> TriangulateDlt(const Eigen::Vector2d& camera_xy,
                                              const Eigen::Vector2d& projector_xy,
                                              const Rigid3d& projector_from_camera);
/// The same with P_projector = [R | t] given as a matrix (no quaternion conversion per call).
std::optional<Eigen::Vector3d> TriangulateDlt(const Eigen::Vector2d& camera_xy,
                                              const Eigen::Vector2d& projector_xy,
                                              const Eigen::Matrix<double, 3, 4>& p_projector);

/// The point on the ray of a projector element (its position `projector_xy` is exact: a
/// design position) whose camera image lies nearest the measured `camera_xy`: the camera
/// point moved perpendicularly onto the element's epipolar line, then intersected. The DLT
/// splits a mismatch between both views, and once the epipolar lines are not parallel to the
/// element rows (a projector in front of or behind the camera) a fraction of a pixel across
/// them moves the point along the ray by millimetres; here only the along-line coordinate
/// sets the depth, as the stereo geometry says it should.
std::optional<Eigen::Vector3d> TriangulateOnProjectorRay(
    const Eigen::Vector2d& camera_xy, const Eigen::Vector2d& projector_xy,
    const Eigen::Matrix<double, 3, 4>& p_projector);

}  // namespace sewer3d
