#pragma once
/// \file
/// The ground truth a simulated run keeps in truth/ (docs/formats.md): odometry error terms,
/// true carrier poses, the defects with their true dimensions. Only the simulator writes these
/// and only evaluation reads them; the processing chain never links this.

#include <Eigen/Core>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/run/capture_run.hpp"
#include "sewer3d/sim/board.hpp"
#include "sewer3d/sim/odometry.hpp"
#include "sewer3d/sim/pipe_world.hpp"

namespace sewer3d {

/// truth/odometry.csv: every sample with its error terms.
void WriteOdometryTruth(const std::filesystem::path& path,
                        const std::vector<OdometrySample>& samples);

/// truth/poses.csv: the true world_from_carrier at each image's time.
struct TruthPose {
  int module = 0;
  int counter = 0;
  ImageKind kind = ImageKind::kPattern;
  double time_s = 0.0;
  double station_mm = 0.0;  ///< carrier centre
  Rigid3d world_from_carrier;
};
void WriteTruthPoses(const std::filesystem::path& path, const std::vector<TruthPose>& poses);
std::vector<TruthPose> ReadTruthPoses(const std::filesystem::path& path);
/// ReadTruthPoses, refusing a file without exactly `images` rows (the run's images).
std::vector<TruthPose> ReadTruthPoses(const std::filesystem::path& path, std::size_t images);

/// truth/camera_gains.csv: each module's white-balance gains (module,gain_r,gain_g,gain_b).
void WriteCameraGains(const std::filesystem::path& path,
                      const std::vector<Eigen::Vector3d>& gains_rgb);

/// A texture image's truth albedo (linear, R, G, B channels; NaN: no surface) as
/// `<path_stem>.png` (8-bit sRGB) and `<path_stem>_linear.png` (16-bit, albedo × 65535), both
/// in the BGR order cv::imwrite expects, 0 where NaN. Creates the folder.
void WriteTruthAlbedo(const std::filesystem::path& path_stem, const cv::Mat3f& albedo_rgb);
/// The two files WriteTruthAlbedo writes for `path_stem`.
std::vector<std::filesystem::path> TruthAlbedoFiles(const std::filesystem::path& path_stem);

/// A simulated calibration capture's truth/poses.json (`simulate calibration`): the board, the
/// realism profile the captures were rendered with ("ideal" or "paper") and each pose's
/// camera_from_board, in the order of the pose folders.
struct CalibrationTruth {
  Checkerboard board;
  std::string realism = "ideal";
  std::vector<Rigid3d> camera_from_board;
};
void WriteCalibrationTruth(const std::filesystem::path& path, const CalibrationTruth& truth);
CalibrationTruth ReadCalibrationTruth(const std::filesystem::path& path);

/// truth/features.json: every joint, feature and deformed section with id, EN 13508-2 main
/// code, station, clock position and true dimensions.
void WriteFeatureTruth(const std::filesystem::path& path, const PipeGeometry& pipe);

}  // namespace sewer3d
