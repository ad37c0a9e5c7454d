#pragma once
/// \file
/// A distortion-free camera for tests that need simple geometry: focal length `focal_px` in
/// both axes, the principal point at the image centre.

#include "sewer3d/camera/camera_model.hpp"

namespace sewer3d::testing {

inline CameraModel PinholeCamera(int width, int height, double focal_px) {
  CameraIntrinsics in;
  in.width = width;
  in.height = height;
  in.fx = in.fy = focal_px;
  in.cx = 0.5 * (width - 1);
  in.cy = 0.5 * (height - 1);
  return CameraModel(in);
}

}  // namespace sewer3d::testing
