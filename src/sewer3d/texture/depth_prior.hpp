#pragma once
/// \file
/// Depth for the pixels the decoder left empty, so that deblur, mapping and shading correction
/// can treat the whole image: a round pipe coaxial with the carrier (carrier frame,
/// run/rig.hpp: z along the carrier axis, origin on it), joined without a step to the measured
/// depth map.

#include <opencv2/core.hpp>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/rigid3.hpp"

namespace sewer3d {

/// Depth z (mm, camera frame) of the wall of a round pipe of `diameter_mm` whose axis is the
/// carrier's z axis (x = y = 0 in the carrier frame), seen from the camera at
/// `carrier_from_camera`; NaN where the ray misses it (the camera outside the pipe, or beyond
/// the lens's fold). `normalised`: the camera's NormalisedCoordinates (texture/shading.hpp).
cv::Mat1f PipePriorDepth(const cv::Mat2f& normalised, const Rigid3d& carrier_from_camera,
                         double diameter_mm);
/// The same, computing the normalised coordinates (the costly part) for this call.
cv::Mat1f PipePriorDepth(const CameraModel& camera, const Rigid3d& carrier_from_camera,
                         double diameter_mm);

/// `depth_mm` with its NaN pixels filled from `prior_mm` (same size) so that the filled depth
/// meets the measured one without a step: the ratio measured / prior, known where both are, is
/// carried smoothly into the holes (push–pull over an image pyramid: averages pulled up to
/// coarser levels, then pushed back into the holes with bilinear interpolation), and a hole
/// takes prior × that ratio. Where no pixel is measured, the prior as it is. Measured pixels
/// are kept unchanged.
cv::Mat1f FillDepthFromPrior(const cv::Mat1f& depth_mm, const cv::Mat1f& prior_mm);

}  // namespace sewer3d
