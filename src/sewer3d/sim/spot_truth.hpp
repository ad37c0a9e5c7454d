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

/// Camera pixels of spot element centres whose rays meet the scene and project into the
/// camera (the pixel may lie outside the image). With `whole_spots_only`, only elements whose
/// disk (plus a pixel of blur) lies inside the projector image: a spot cut by the image's edge
/// has no meaningful centre. Without it, every element the projector lights at least in part.
/// Occlusion is not tested: the scenes here are seen from inside or in front.
std::vector<Eigen::Vector2d> ProjectedSpotCentres(const ModuleDescription& module,
                                                  const BinaryArray& pattern, const Scene& scene,
                                                  bool whole_spots_only = true);

}  // namespace sewer3d
