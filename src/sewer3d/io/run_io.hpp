#pragma once
/// \file
/// The files of a capture run (docs/formats.md): rig.json, the acquisition index, odometry,
/// and the ground truth under truth/. Errors are FileError naming the file (and line).

#include <filesystem>
#include <string>
#include <vector>

#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/pattern/binary_array.hpp"
#include "sewer3d/sim/odometry.hpp"
#include "sewer3d/sim/pipe_world.hpp"
#include "sewer3d/sim/rig.hpp"
#include "sewer3d/sim/trajectory.hpp"

namespace sewer3d {

struct LoadedRig {
  Rig rig;
  std::vector<BinaryArray> patterns;  ///< each module's pattern matrix
};

/// rig.json: carrier size and, per module, its name, clock, module description (the module
/// file's form; pattern.matrix relative to rig.json) and carrier_from_camera.
std::string RigToJson(const Rig& rig);
void WriteRig(const std::filesystem::path& path, const Rig& rig);
LoadedRig ReadRig(const std::filesystem::path& path);

/// One image of the run, as listed in acquisitions.csv.
struct IndexEntry {
  int module = 0;
  int counter = 0;
  ImageKind kind = ImageKind::kPattern;
  double time_s = 0.0;  ///< middle of the exposure
  double exposure_ms = 0.0;
  std::string file;  ///< relative to the run folder
};
void WriteIndex(const std::filesystem::path& path, const std::vector<IndexEntry>& entries);
std::vector<IndexEntry> ReadIndex(const std::filesystem::path& path);

/// odometry.csv: what the robot reports (time_s, distance_mm).
void WriteOdometry(const std::filesystem::path& path, const std::vector<OdometrySample>& samples);
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

/// truth/features.json: every joint, feature and deformed section with id, EN 13508-2 main
/// code, station, clock position and true dimensions.
void WriteFeatureTruth(const std::filesystem::path& path, const PipeGeometry& pipe);

}  // namespace sewer3d
