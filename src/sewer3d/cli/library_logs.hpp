#pragma once
/// \file
/// The libraries' own logging (Ceres through glog, OpenCV, and std::cerr, which OpenCV's
/// decoders write to) off, so that an error is the one
/// line main prints; SEWER3D_LIBRARY_LOGS=1 in the environment keeps them for debugging.

namespace sewer3d::cli {

void QuietLibraryLogs();

}  // namespace sewer3d::cli
