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
#include "sewer3d/sim/surface.hpp"

namespace sewer3d {

/// Camera pixels of spot element centres whose rays meet the scene and project into the
/// camera (the pixel may lie outside the image). With `whole_spots_only`, only elements whose
/// disk (plus a pixel of blur) lies inside the projector image: a spot cut by the image's edge
/// has no meaningful centre. Without it, every element the projector lights at least in part.
/// Occlusion is not tested: the scenes here are seen from inside or in front.
std::vector<Eigen::Vector2d> ProjectedSpotCentres(const ModuleDescription& module,
                                                  const BinaryArray& pattern, const Scene& scene,
                                                  bool whole_spots_only = true);

/// A lit element's spot as the camera sees it.
struct VisibleSpot {
  int row = 0, col = 0;   ///< projector element, absolute indices
  Eigen::Vector2d pixel;  ///< camera pixel of the element centre's point
  SurfaceHit hit;         ///< where the element centre's ray meets the surface
};

/// The whole spots (as ProjectedSpotCentres with whole_spots_only) whose centre's point the
/// camera sees: inside the image by `margin_px` and not hidden behind nearer surface (the
/// camera's ray to the pixel meets the surface within `occlusion_tolerance_mm` of the point).
/// What a perfect decoder would triangulate: the oracle of the decoder's tests.
std::vector<VisibleSpot> VisibleSpots(const ModuleDescription& module, const BinaryArray& pattern,
                                      const Surface& surface, double margin_px = 2.0,
                                      double occlusion_tolerance_mm = 0.5);

}  // namespace sewer3d
