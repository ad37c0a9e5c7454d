#pragma once
/// \file
/// Ground truth of the projected pattern: where the centre of every spot element lands in the
/// camera image, computed geometrically (projector ray through the element centre -> scene ->
/// camera), independently of the renderer's sampling.

#include <Eigen/Core>

#include <vector>

#include "sewer3d/camera/module.hpp"
#include "sewer3d/pattern/binary_array.hpp"
#include "sewer3d/sim/scene.hpp"

namespace sewer3d {

/// Camera pixels of the spot elements whose whole disk (plus a pixel of blur) lies inside the projector image and whose
/// rays meet the scene and project into the camera (the pixel may lie outside the image).
/// Occlusion is not tested: the scenes here are seen from inside or in front.
std::vector<Eigen::Vector2d> ProjectedSpotCentres(const ModuleDescription& module,
                                                  const BinaryArray& pattern, const Scene& scene);

}  // namespace sewer3d
