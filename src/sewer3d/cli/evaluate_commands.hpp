#pragma once
/// \file
/// The parts of `sewer3d evaluate`: a surface fitted to a cloud, and the judges of a
/// processing stage on a simulated run.

#include <filesystem>
#include <string>

namespace sewer3d::cli {

/// `sewer3d evaluate plane|cylinder --cloud PLY [--truth scene.json] [--inner-fraction F]
/// [--out DIR]`: fits `surface` to the inner part of the cloud and prints the fit (and the
/// errors against the true scene); with `out`, writes DIR/residuals.png (every point's signed
/// distance from the fit where the camera sees it) and, with the truth,
/// DIR/truth_residuals.png. FileError for a cloud that fits no such surface. Returns the exit
/// code.
int RunEvaluateSurface(const std::string& surface, const std::string& cloud,
                       const std::string& truth_file, double inner_fraction,
                       const std::string& out);

/// `sewer3d evaluate rgbd --run RUN --workspace WS [--out DIR]`: prints the colour figures,
/// writes DIR/evaluation.json and DIR/colour_montage.png; returns the exit code.
/// `smoothing_px`: colours are compared after a box mean of this side (1: per pixel).
int RunEvaluateRgbd(const std::string& run, const std::string& workspace, const std::string& out,
                    int smoothing_px);

/// `sewer3d evaluate registration --run RUN --workspace WS [--out DIR]`: prints the trajectory
/// error (overall, per material) and the accepted edges' errors and NEES, writes
/// DIR/evaluation.json (default WS/evaluation/registration); returns the exit code.
int RunEvaluateRegistration(const std::string& run, const std::string& workspace,
                            const std::string& out);

/// `sewer3d evaluate model --run RUN --workspace WS [--out DIR] [--stride N]`: prints the model
/// surface's errors against the true wall (overall, per coverage class, per material) and the
/// circumference differences, writes DIR/evaluation.json, DIR/error_map.png (±1 mm) and
/// DIR/error_map_after_axis_offset.png (±0.5 mm) (default WS/evaluation/model); `stride` 0:
/// automatic. Returns the exit code.
int RunEvaluateModel(const std::string& run, const std::string& workspace, const std::string& out,
                     int stride);

/// `sewer3d evaluate inspection --run RUN --workspace WS [--local-alignment-mm W] [--out DIR]`:
/// prints which true items
/// the observations found (with their errors), the invented ones and the profile's errors,
/// writes DIR/evaluation.json (default WS/evaluation/inspection). Returns the exit code.
int RunEvaluateInspection(const std::string& run, const std::string& workspace,
                          double local_alignment_mm, const std::string& out);

/// `sewer3d evaluate calibration --captures DIR --module FILE [--out FILE]`: prints the
/// calibrated module (FILE, from `calibrate module`, with its standard deviations) against the
/// module DIR's captures were simulated with and against the nearest module a file can hold
/// for their lenses (docs/calibration.md); writes the table as JSON to `out` when given.
/// Returns the exit code.
int RunEvaluateCalibration(const std::string& captures, const std::string& module,
                           const std::string& out);

/// A warning that `workspace`'s workspace.json records the stage `kind` evaluates as stale or
/// not done (the evaluation then judges an earlier run's outputs); empty when it is done.
std::string StageNotDone(const std::filesystem::path& workspace, const std::string& kind);

}  // namespace sewer3d::cli
