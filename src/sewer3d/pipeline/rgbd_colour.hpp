#pragma once
/// \file
/// The RGB-D stage's colour pass over one acquisition (after its geometry pass): the colour
/// image aligned with the depth map, the cloud recoloured from it, and the acquisition report
/// (io/rgbd_io.hpp).

#include <filesystem>

#include "sewer3d/pipeline/rgbd_geometry.hpp"
#include "sewer3d/run/capture_run.hpp"

namespace sewer3d {

/// Where the colour of the RGB-D outputs comes from, as recorded in workspace.json and the
/// reports.
inline constexpr const char* kRgbdColorSource = "texture_before, uncorrected";

/// The colour pass of acquisition `a` into `rgbd_folder` (`WS/rgbd`): skipped when its report
/// exists; failed (in the result, never thrown) when its geometry is missing or an image is bad.
RgbdAcquisitionResult RgbdColourPass(const CaptureRun& run, const Acquisition& a,
                                     const std::filesystem::path& rgbd_folder);

}  // namespace sewer3d
