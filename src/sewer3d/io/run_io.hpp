#pragma once
/// \file
/// The files of a capture run (docs/formats.md): run.json, rig.json, the image index
/// acquisitions.csv and odometry.csv, and LoadRun, which reads and checks a whole run. The
/// simulator's truth/ is not read here (simio/truth_io.hpp): the processing chain never sees
/// it. Errors are FileError naming the file (and line or field).

#include <filesystem>
#include <string>
#include <vector>

#include "sewer3d/run/capture_run.hpp"

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

/// run.json with the file names rig.json, acquisitions.csv, odometry.csv and the counts.
struct RunCounts {
  int modules = 0, acquisitions = 0, images = 0;
  double simulation_seconds = 0.0;  ///< simulated runs: time spent simulating
};
void WriteRunInfo(const std::filesystem::path& path, const RunInfo& info, const RunCounts& counts);
RunInfo ReadRunInfo(const std::filesystem::path& path);
/// run.json's counts; -1 for a count it does not give.
RunCounts ReadRunCounts(const std::filesystem::path& path);

/// acquisitions.csv: every image of the run, sorted by time.
void WriteIndex(const std::filesystem::path& path, const std::vector<RunImage>& images);
/// Checks each row's fields (module and counter non-negative integers, known image kind, finite
/// time, exposure ≥ 0, a relative file name inside the run) and that rows are sorted by time.
std::vector<RunImage> ReadIndex(const std::filesystem::path& path);

/// odometry.csv: time_s,distance_mm; times strictly increasing.
void WriteOdometry(const std::filesystem::path& path, const std::vector<OdometryReading>& readings);
std::vector<OdometryReading> ReadOdometry(const std::filesystem::path& path);

struct LoadRunOptions {
  /// Accept a run whose run.json says "complete": false (a capture that stopped part-way):
  /// images whose file is missing are dropped. Otherwise such a run is refused.
  bool allow_incomplete = false;
};

/// Reads run.json, rig.json (with the pattern matrices), acquisitions.csv and odometry.csv of
/// the run folder `folder` and checks them against each other: every image's module exists in
/// the rig (else FileError naming rig.json), no image is listed twice. A listed image whose
/// file is missing is kept with `missing` set (its acquisition fails in the rgbd stage, the
/// others are processed). The odometry goes through CheckOdometry: `run.odometry` holds the
/// readings kept, `run.odometry_findings` what was dropped and the gaps. Reads no image.
CaptureRun LoadRun(const std::filesystem::path& folder, const LoadRunOptions& options = {});

}  // namespace sewer3d
