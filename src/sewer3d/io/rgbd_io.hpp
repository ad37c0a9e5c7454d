#pragma once
/// \file
/// The files of one RGB-D acquisition in a processing workspace (DESIGN.md contract
/// "processing workspace"): `WS/rgbd/m<k>/<counter>_color.png`, `_depth.tiff`, `_cloud.ply` and
/// `_report.json`, each written atomically, the report last: an acquisition whose report exists
/// is complete. Errors are FileError.

#include <filesystem>
#include <opencv2/core.hpp>
#include <string>

#include "sewer3d/triangulate/reconstruct_frame.hpp"

namespace sewer3d {

/// The files of acquisition (module, counter) under the stage folder `rgbd_folder`
/// (`WS/rgbd`); the counter has 6 digits as in the run's image names.
struct RgbdFiles {
  std::filesystem::path color;          ///< 8-bit RGB PNG, the camera image size
  std::filesystem::path depth;          ///< float32 TIFF, z in mm in the camera frame, NaN = none
  std::filesystem::path depth_preview;  ///< colour-mapped depth for people (near red, far blue)
  std::filesystem::path cloud;          ///< PLY, points in mm in the camera frame, with colours
  std::filesystem::path report;         ///< JSON, written last
};
RgbdFiles RgbdAcquisitionFiles(const std::filesystem::path& rgbd_folder, int module, int counter);

/// True when the acquisition's report exists, i.e. it was finished by an earlier run.
bool RgbdAcquisitionDone(const RgbdFiles& files);

/// Writes colour (`color_bgr`, OpenCV's BGR order; the PNG holds RGB), then `frame` as
/// reconstruction_io.hpp's WriteFrameReconstruction does (into a temporary folder beside, whose
/// files are renamed into place: depth map, preview, cloud), then the report: the frame
/// report's fields (`image` = the pattern image) merged with `extra_json` (a JSON object as
/// text, e.g. module, counter, total seconds; its members win, objects are merged).
void WriteRgbdAcquisition(const RgbdFiles& files, const cv::Mat3b& color_bgr,
                          const FrameReconstruction& frame, const std::string& image,
                          const std::string& extra_json);

}  // namespace sewer3d
