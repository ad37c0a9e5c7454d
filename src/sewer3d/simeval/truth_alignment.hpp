#pragma once
/// \file
/// The model frame of a processed simulated run aligned onto the truth's world: the registered
/// camera centres (WS/registration/poses.csv) against the true ones (truth/poses.csv with
/// rig.json's carrier_from_camera), one rigid transform by Umeyama (no scale) on each camera's
/// centre and the point 150 mm along its optical axis (the centres alone are nearly collinear:
/// the roll about the carrier's path would be free). Shared by the registration, model and
/// inspection evaluations, so all judge the same alignment.

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <vector>

#include "sewer3d/core/rigid3.hpp"
#include "sewer3d/io/registration_io.hpp"
#include "sewer3d/model/pipe_map.hpp"
#include "sewer3d/run/capture_run.hpp"

namespace sewer3d {

struct TruthAlignment {
  std::map<int, Rigid3d> truth;            ///< registration vertex id → true world_from_camera
  std::vector<RegistrationPoseRow> poses;  ///< WS/registration/poses.csv
  Eigen::Matrix3Xd model_centres;          ///< the poses' camera centres (model frame)
  Eigen::Matrix3Xd true_centres;           ///< the same cameras' true centres (world)
  Rigid3d truth_from_model;                ///< identity when fewer than 3 poses
};

/// truth_from_model of cameras posed in both frames (world_from_camera each, same order, at
/// least 3): Umeyama without scale on every camera's centre and the point 150 mm along its
/// optical axis.
Rigid3d AlignCameras(const std::vector<Rigid3d>& model, const std::vector<Rigid3d>& world);

/// Reads truth/poses.csv of `run_folder` and WS/registration/poses.csv and aligns them;
/// FileError when a file is missing or malformed, or a registered pose has no truth.
TruthAlignment AlignRegistrationToTruth(const CaptureRun& run,
                                        const std::filesystem::path& run_folder,
                                        const std::filesystem::path& workspace);

/// truth_from_model of the cameras whose centres lie within ± `half_window_mm` of
/// `station_mm` along `centreline` (model stations): where one rigid alignment cannot hold a
/// whole trajectory (a long run whose registration drifts or follows an odometry slip), what
/// the model says of a place is judged against the truth aligned there. The whole run's
/// alignment where fewer than 6 cameras lie in the window.
Rigid3d LocalTruthFromModel(const TruthAlignment& alignment, const Centreline& centreline,
                            double station_mm, double half_window_mm);

}  // namespace sewer3d
