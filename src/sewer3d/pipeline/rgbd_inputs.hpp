#pragma once
/// \file
/// The RGB-D stage's checks on its inputs that do not stop it but that a person must hear of
/// (docs/rgbd.md, "Inputs it warns of"): a pattern matrix that breaks the constraints the
/// decoder relies on; images replaced since an earlier run processed them (their acquisitions
/// are redone); a camera that repeats itself (a pattern image byte for byte the previous
/// counter's); blown-out or black texture images.

#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "sewer3d/pattern/constraints.hpp"
#include "sewer3d/pipeline/workspace.hpp"
#include "sewer3d/run/capture_run.hpp"

namespace sewer3d {

/// The stamps (io/file_stamp.hpp) of the acquisition's images that exist, keyed by kind, for
/// its geometry report's "inputs": {"pattern": {"file", "bytes", "mtime_ns", "hash"}, ...}.
nlohmann::json InputStamps(const CaptureRun& run, const Acquisition& a);

/// For every acquisition the geometry pass finished before whose images are no longer those
/// its geometry report stamped, removes its reports so that both passes redo it; one line per
/// acquisition redone, naming the first changed image. Reports without stamps are kept.
std::vector<std::string> ForgetChangedAcquisitions(const CaptureRun& run,
                                                   const std::vector<Acquisition>& acquisitions,
                                                   const std::filesystem::path& rgbd_folder);

/// True when every acquisition of the run is finished in `rgbd_folder` (both passes) from the
/// images the run holds now (their stamps); false as soon as one is missing or changed. About
/// the cost of a resumed stage with nothing to do: a report read and a stat per image.
bool RgbdUpToDate(const CaptureRun& run, const std::filesystem::path& rgbd_folder);

/// "" when the rgbd outputs in `workspace` are those of the run as it is now, else why not, in
/// words naming the folder or workspace.json, for a later stage run on its own (register
/// refuses, model warns): the stage is recorded stale (the run's rig.json, pattern matrices or
/// acquisitions.csv changed since it ran), or not RgbdUpToDate (rgbd unfinished, or images added
/// or replaced since).
std::string RgbdBehind(const CaptureRun& run, const Workspace& workspace);

/// One line per module whose pattern matrix, by the constraints it satisfies (`inferred`, one
/// per module, InferConstraints), breaks the pattern constraints a matrix is made with
/// (PatternConstraints' defaults): touching spots, or windows that differ in too few spots or
/// hold too few, so decoding fails or errs. Empty when every matrix keeps them.
std::vector<std::string> PatternMatrixWarnings(const CaptureRun& run,
                                               const std::vector<PatternConstraints>& inferred);

/// One line per acquisition whose pattern image is byte for byte one seen before (stamps of
/// the geometry reports): the same module's previous counter (a camera that delivers the same
/// frame again, which the odometry places at two stations), or any other acquisition (an image
/// copied or filed under the wrong module).
std::vector<std::string> RepeatedImageWarnings(const CaptureRun& run,
                                               const std::vector<Acquisition>& acquisitions,
                                               const std::filesystem::path& rgbd_folder);

/// "N % of the pixels are saturated (blown out) ..." or "... black ..." when more than half of
/// the texture image's pixels are; empty otherwise. `linear` is BGR in [0, 1].
std::string ExposureProblem(const cv::Mat3f& linear);

}  // namespace sewer3d
