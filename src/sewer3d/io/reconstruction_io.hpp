#pragma once
/// \file
/// Writing one frame's reconstruction (`sewer3d reconstruct`'s output folder). Errors are
/// FileError.

#include <filesystem>
#include <string>

#include "sewer3d/triangulate/reconstruct_frame.hpp"

namespace sewer3d {

/// Writes into `folder` (created): cloud.ply (points in the camera frame, with colours when the
/// frame has them), depth.tiff (float32 z in mm, NaN = none), depth.png (colour-mapped
/// preview) and report.json (WriteFrameReport). `image` is the pattern image's path as the
/// user gave it, recorded in the report.
void WriteFrameReconstruction(const std::filesystem::path& folder, const FrameReconstruction& frame,
                              const std::string& image);

/// report.json: the image path and every count and stage time of the report, keys sorted
/// (spots_found, lattice_groups, …, rejected {reason: count}, points, seconds {stage: s}).
void WriteFrameReport(const std::filesystem::path& path, const FrameReport& report,
                      const std::string& image);

}  // namespace sewer3d
