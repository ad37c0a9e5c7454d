#pragma once
/// \file
/// What the model stage takes from one registered RGB-D acquisition (model_stage.hpp): depth
/// samples in the model frame for the centreline fit, and every pixel with depth (and its
/// corrected colour) for the maps.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "sewer3d/camera/camera_model.hpp"
#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/model/map_accumulator.hpp"
#include "sewer3d/model/module_offsets.hpp"
#include "sewer3d/model/pipe_map.hpp"

namespace sewer3d {

/// An acquisition with its registered pose and the stations its samples span.
struct ModelAcquisition {
  int module = 0;
  int counter = 0;
  Rigid3d world_from_camera;
  double station_min_mm = 0.0, station_max_mm = 0.0;
};

/// About `target` points of the depth map (a regular pixel grid) in the model frame.
std::vector<Eigen::Vector3d> FitSamples(const cv::Mat1f& depth_mm, const CameraModel& camera,
                                        const Rigid3d& world_from_camera, int target);

/// Adds the fit samples of every acquisition (`samples[i]` of `acquisitions[i]`, model frame)
/// to `estimator` as wall samples of its module: cylindrical coordinates about `centreline`,
/// and the cosine of each ray's incidence on the wall (taken as radial).
void AddWallSamples(ModuleOffsetEstimator& estimator, const Centreline& centreline,
                    const std::vector<ModelAcquisition>& acquisitions,
                    const std::vector<std::vector<Eigen::Vector3d>>& samples);

/// How pixels become weighted map samples.
struct PixelWeighting {
  int pixel_step = 1;
  double feather_px = 50.0;
  double depth_sigma_ref_mm = 0.03;
  double depth_ref_mm = 150.0;
  double range_offset_mm = 0.0;  ///< taken off every ray's range (the module's, ModuleOffsets)
};

/// The depth map's holes enclosed along a row or a column (pixels without depth between two
/// with depth; not those reaching the image's border, beyond the lit view), each with the
/// depth interpolated along its row (or, where the row's run reaches the border, its
/// column); NaN elsewhere.
cv::Mat1f EnclosedHoleDepths(const cv::Mat1f& depth_mm);

/// Adds every pixel_step-th pixel with depth of the acquisition (colour from `color_bgr`) to
/// `maps`, weighted by DepthWeight × BorderFeather. `normalised`: the camera's
/// NormalisedCoordinates (texture/shading.hpp), computed once per module rather than
/// unprojecting every pixel of every acquisition again. The acquisition's enclosed holes
/// (EnclosedHoleDepths) are marked seen (MapAccumulator::AddSeen: hole edges at the frames'
/// median). Returns the samples the tile took.
long long AddAcquisitionPixels(MapAccumulator& maps, const cv::Mat1f& depth_mm,
                               const cv::Mat3b& color_bgr, const cv::Mat2f& normalised,
                               const Rigid3d& world_from_camera, const PixelWeighting& weighting);

}  // namespace sewer3d
