#pragma once
/// \file
/// The files of one RGB-D acquisition in a processing workspace (DESIGN.md contract
/// "processing workspace"; docs/rgbd.md): `WS/rgbd/m<k>/<counter>_color.png`, `_depth.tiff`,
/// `_depth_preview.png`, `_cloud.ply`, `_geometry.json` and `_report.json`, each written
/// atomically. The stage writes them in two passes: geometry (depth map, preview, cloud without
/// colours, `_geometry.json` last) and colour (colour image, the cloud
/// recoloured, `_report.json` last). An acquisition whose report exists is complete; one whose
/// geometry file exists has its depth map and cloud. Errors are FileError.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "sewer3d/triangulate/reconstruct_frame.hpp"

namespace sewer3d {

/// The files of acquisition (module, counter) under the stage folder `rgbd_folder`
/// (`WS/rgbd`); the counter has 6 digits as in the run's image names.
struct RgbdFiles {
  std::filesystem::path color;          ///< 8-bit RGB PNG, the camera image size
  std::filesystem::path depth;          ///< float32 TIFF, z in mm in the camera frame, NaN = none
  std::filesystem::path depth_preview;  ///< colour-mapped depth for people (near red, far blue)
  std::filesystem::path cloud;          ///< PLY, points in mm in the camera frame, with colours
  std::filesystem::path geometry;       ///< JSON, the geometry pass's report, written last of it
  std::filesystem::path report;         ///< JSON, the acquisition's report, written last
};
RgbdFiles RgbdAcquisitionFiles(const std::filesystem::path& rgbd_folder, int module, int counter);

/// True when the acquisition's report exists, i.e. it was finished by an earlier run, and the
/// depth map, colour image and cloud still have the sizes it recorded (`file_bytes`).
bool RgbdAcquisitionDone(const RgbdFiles& files);
/// The first file of a finished acquisition whose size is not the one its report recorded
/// (cut short or replaced since: a copy broken off, a full disk); empty when none is, or when
/// the acquisition is not finished.
std::string RgbdDamagedFile(const RgbdFiles& files);
/// True when the geometry pass finished the acquisition (its geometry report exists).
bool RgbdGeometryDone(const RgbdFiles& files);

/// The geometry pass's files: `frame` as reconstruction_io.hpp's WriteFrameReconstruction
/// writes it (into a temporary folder beside, whose files are renamed into place: depth map,
/// preview, cloud), then the geometry report: the frame report's fields (`image` = the pattern
/// image) merged with `extra_json` (a JSON object as text; its members win, objects merge).
void WriteRgbdGeometry(const RgbdFiles& files, const FrameReconstruction& frame,
                       const std::string& image, const std::string& extra_json);

/// What the colour pass reads back of the geometry pass.
struct RgbdGeometry {
  cv::Mat1f depth_mm;                   ///< NaN = none
  std::vector<Eigen::Vector3d> points;  ///< the cloud, camera frame, mm
  std::string report_json;              ///< the geometry report (a JSON object)
};
/// Reads the geometry pass's depth map, cloud and report; FileError naming the file at fault.
RgbdGeometry ReadRgbdGeometry(const RgbdFiles& files);

/// The colour pass's files: the colour image (`color_bgr`, OpenCV's BGR order; the PNG holds
/// RGB), the cloud rewritten with `colours` (one RGB per point of `points`), then the report
/// `report_json` (a JSON object as text) last.
void WriteRgbdColour(const RgbdFiles& files, const cv::Mat3b& color_bgr,
                     const std::vector<Eigen::Vector3d>& points,
                     const std::vector<std::array<std::uint8_t, 3>>& colours,
                     const std::string& report_json);

}  // namespace sewer3d
