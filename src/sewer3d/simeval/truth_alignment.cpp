#include "sewer3d/simeval/truth_alignment.hpp"

#include <Eigen/Geometry>
#include <string>

#include "sewer3d/core/check.hpp"
#include "sewer3d/io/file_error.hpp"
#include "sewer3d/model/unroll.hpp"
#include "sewer3d/simio/truth_io.hpp"

namespace sewer3d {

Rigid3d AlignCameras(const std::vector<Rigid3d>& model, const std::vector<Rigid3d>& world) {
  SEWER3D_CHECK(model.size() == world.size());
  const auto n = static_cast<Eigen::Index>(model.size());
  // The centres alone lie near one line (the carrier's path: its cameras sit on its axis),
  // which leaves the roll about it to the carrier's wander; a point on each optical axis,
  // where the camera looks at the wall, fixes it.
  constexpr double kViewMm = 150.0;
  Eigen::Matrix3Xd m(3, 2 * n), w(3, 2 * n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto k = static_cast<size_t>(i);
    m.col(2 * i) = model[k].translation;
    m.col(2 * i + 1) = model[k] * Eigen::Vector3d(0.0, 0.0, kViewMm);
    w.col(2 * i) = world[k].translation;
    w.col(2 * i + 1) = world[k] * Eigen::Vector3d(0.0, 0.0, kViewMm);
  }
  const Eigen::Matrix4d t = Eigen::umeyama(m, w, false);
  return {Eigen::Matrix3d(t.topLeftCorner<3, 3>()), Eigen::Vector3d(t.topRightCorner<3, 1>())};
}

TruthAlignment AlignRegistrationToTruth(const CaptureRun& run,
                                        const std::filesystem::path& run_folder,
                                        const std::filesystem::path& workspace) {
  TruthAlignment a;
  for (const TruthPose& t : ReadTruthPoses(run_folder / "truth" / "poses.csv", run.images.size())) {
    if (t.kind != ImageKind::kPattern || t.module >= static_cast<int>(run.rig.modules.size()))
      continue;
    a.truth[RegistrationVertexId(t.module, t.counter)] =
        t.world_from_carrier * run.rig.modules[t.module].carrier_from_camera;
  }
  const std::filesystem::path poses_file = workspace / "registration" / "poses.csv";
  a.poses = ReadRegistrationPoses(poses_file);
  const auto n = static_cast<Eigen::Index>(a.poses.size());
  a.model_centres.resize(3, n);
  a.true_centres.resize(3, n);
  std::vector<Rigid3d> model, world;
  for (Eigen::Index i = 0; i < n; ++i) {
    const RegistrationPoseRow& pose = a.poses[static_cast<size_t>(i)];
    const auto it = a.truth.find(RegistrationVertexId(pose.module, pose.counter));
    if (it == a.truth.end()) {
      throw FileError(run_folder / "truth" / "poses.csv",
                      "no true pose of m" + std::to_string(pose.module) + " counter " +
                          std::to_string(pose.counter) + ", which " + poses_file.string() +
                          " lists: is the workspace from another run, or the truth cut short?");
    }
    model.push_back(pose.world_from_camera);
    world.push_back(it->second);
    a.model_centres.col(i) = pose.world_from_camera.translation;
    a.true_centres.col(i) = it->second.translation;
  }
  if (n >= 3) a.truth_from_model = AlignCameras(model, world);
  return a;
}

Rigid3d LocalTruthFromModel(const TruthAlignment& alignment, const Centreline& centreline,
                            double station_mm, double half_window_mm) {
  std::vector<Rigid3d> model, world;
  for (std::size_t i = 0; i < alignment.poses.size(); ++i) {
    const Eigen::Vector3d centre = alignment.model_centres.col(static_cast<Eigen::Index>(i));
    if (std::abs(Unroll(centreline, centre, centreline.station0_mm).station_mm - station_mm) >
        half_window_mm)
      continue;
    const RegistrationPoseRow& pose = alignment.poses[i];
    model.push_back(pose.world_from_camera);
    world.push_back(alignment.truth.at(RegistrationVertexId(pose.module, pose.counter)));
  }
  constexpr std::size_t kMinCameras = 6;
  return model.size() >= kMinCameras ? AlignCameras(model, world) : alignment.truth_from_model;
}

}  // namespace sewer3d
