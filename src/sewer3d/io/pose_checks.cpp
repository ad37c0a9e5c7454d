#include "sewer3d/io/pose_checks.hpp"

#include <fmt/core.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <tuple>

namespace sewer3d {
namespace {

// Each module's rows together, in time order (the counter breaks ties).
void SortByModuleAndTime(std::vector<RegistrationPoseRow>& rows) {
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) {
    return std::tie(a.module, a.time_s, a.counter) < std::tie(b.module, b.time_s, b.counter);
  });
}

// An acquisition's carrier origin in the model frame.
struct CarrierAt {
  double time_s = 0.0;
  int module = 0;
  int counter = 0;
  Eigen::Vector3d origin;
};

std::vector<CarrierAt> CarrierOrigins(const std::vector<RegistrationPoseRow>& rows,
                                      const Rig& rig) {
  std::vector<CarrierAt> carriers;
  for (const RegistrationPoseRow& row : rows) {
    if (row.module < 0 || row.module >= static_cast<int>(rig.modules.size())) continue;
    const Rigid3d world_from_carrier =
        row.world_from_camera * rig.modules[row.module].carrier_from_camera.Inverse();
    carriers.push_back({row.time_s, row.module, row.counter, world_from_carrier.translation});
  }
  std::sort(carriers.begin(), carriers.end(),
            [](const auto& a, const auto& b) { return a.time_s < b.time_s; });
  return carriers;
}

// How far the carrier may have moved between two times: the odometry's distance, or 2 m/s.
double CarrierTravelBound(const std::vector<OdometryReading>& readings, double t0, double t1) {
  constexpr double kMaxSpeedMmS = 2000.0;
  const auto from = OdometryDistanceAt(readings, t0);
  const auto to = OdometryDistanceAt(readings, t1);
  if (from && to) return std::abs(*to - *from);
  return kMaxSpeedMmS * std::abs(t1 - t0);
}

}  // namespace

std::string PoseJumpProblem(std::vector<RegistrationPoseRow> rows) {
  constexpr double kSlackMm = 500.0, kMaxSpeedMmS = 2000.0;
  SortByModuleAndTime(rows);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const RegistrationPoseRow &a = rows[i - 1], &b = rows[i];
    if (a.module != b.module) continue;
    const double apart_mm =
        (b.world_from_camera.translation - a.world_from_camera.translation).norm();
    const double dt_s = b.time_s - a.time_s;
    if (!(apart_mm <= kSlackMm + kMaxSpeedMmS * dt_s)) {
      return fmt::format(
          "module {}'s acquisitions {} and {} lie {:.4g} m apart, {:.3g} s apart in time: faster "
          "than a crawler moves (an edited file, or a registration gone wrong); run register "
          "again",
          a.module, a.counter, b.counter, apart_mm / 1000.0, dt_s);
    }
  }
  return "";
}

std::string PoseTravelProblem(std::vector<RegistrationPoseRow> rows,
                              const std::vector<OdometryReading>& readings) {
  constexpr double kMinOdometryMm = 20.0, kFactor = 5.0;
  SortByModuleAndTime(rows);
  for (std::size_t first = 0; first < rows.size();) {
    std::size_t last = first;
    while (last + 1 < rows.size() && rows[last + 1].module == rows[first].module) ++last;
    const RegistrationPoseRow &a = rows[first], &b = rows[last];
    first = last + 1;
    const auto from = OdometryDistanceAt(readings, a.time_s);
    const auto to = OdometryDistanceAt(readings, b.time_s);
    if (!from || !to || std::abs(*to - *from) < kMinOdometryMm) continue;
    const double odometry_mm = std::abs(*to - *from);
    const double poses_mm =
        (b.world_from_camera.translation - a.world_from_camera.translation).norm();
    if (poses_mm * kFactor >= odometry_mm && poses_mm <= kFactor * odometry_mm) continue;
    return fmt::format(
        "module {}'s camera moves {:.4g} mm from acquisition {} to {}, the odometry {:.4g} mm "
        "over the same time: poses in other units than mm, or of another run? run register "
        "again",
        a.module, poses_mm, a.counter, b.counter, odometry_mm);
  }
  return "";
}

std::string PoseDirectionProblem(std::vector<RegistrationPoseRow> rows,
                                 const std::vector<OdometryReading>& readings, const Rig& rig) {
  constexpr double kMinStepMm = 20.0, kMinForward = 0.5;
  SortByModuleAndTime(rows);
  for (std::size_t first = 0; first < rows.size();) {
    std::size_t last = first;
    while (last + 1 < rows.size() && rows[last + 1].module == rows[first].module) ++last;
    const int module = rows[first].module;
    const std::size_t begin = first;
    first = last + 1;
    if (module < 0 || module >= static_cast<int>(rig.modules.size())) continue;
    // The carrier axis in the camera's frame.
    const Eigen::Vector3d axis =
        rig.modules[module].carrier_from_camera.RotationMatrix().transpose().col(2);
    int steps = 0, against = 0;
    std::size_t shown = begin, shown_to = begin;
    double shown_forward = 0.0, shown_odometry = 0.0;
    for (std::size_t a = begin, b = begin + 1; b <= last; ++b) {
      const auto from = OdometryDistanceAt(readings, rows[a].time_s);
      const auto to = OdometryDistanceAt(readings, rows[b].time_s);
      if (!from || !to) continue;
      const double odometry_mm = *to - *from;
      if (odometry_mm < kMinStepMm) continue;
      const Rigid3d& pa = rows[a].world_from_camera;
      const double forward = axis.dot(pa.RotationMatrix().transpose() *
                                      (rows[b].world_from_camera.translation - pa.translation));
      ++steps;
      if (forward < kMinForward * odometry_mm) {
        if (against++ == 0) {
          shown = a;
          shown_to = b;
          shown_forward = forward;
          shown_odometry = odometry_mm;
        }
      }
      a = b;
    }
    if (steps == 0 || 2 * against <= steps) continue;
    return fmt::format(
        "module {}'s camera moves {:.4g} mm along the carrier axis from acquisition {} to {}, "
        "the odometry {:.4g} mm forward ({} of its {} steps against the odometry): poses as "
        "camera_from_world, or with an axis negated? run register again",
        module, shown_forward, rows[shown].counter, rows[shown_to].counter, shown_odometry, against,
        steps);
  }
  return "";
}

std::string PoseRigProblem(const std::vector<RegistrationPoseRow>& rows,
                           const std::vector<OdometryReading>& readings, const Rig& rig) {
  constexpr double kWindowS = 0.25, kSlackMm = 25.0;
  const std::vector<CarrierAt> carriers = CarrierOrigins(rows, rig);
  for (std::size_t i = 0; i < carriers.size(); ++i) {
    const CarrierAt& a = carriers[i];
    int partners = 0, apart = 0;
    double nearest_mm = INFINITY;  // the disagreeing partner's offset closest to allowed
    for (std::size_t j = 0; j < carriers.size(); ++j) {
      const CarrierAt& b = carriers[j];
      if (b.module == a.module || std::abs(b.time_s - a.time_s) > kWindowS) continue;
      ++partners;
      const double offset_mm = (b.origin - a.origin).norm();
      if (offset_mm <= kSlackMm + CarrierTravelBound(readings, a.time_s, b.time_s)) continue;
      ++apart;
      nearest_mm = std::min(nearest_mm, offset_mm);
    }
    if (partners < 2 || 2 * apart <= partners) continue;
    return fmt::format(
        "module {}'s acquisition {} puts the carrier {:.3g} mm or more from where {} of the {} "
        "other modules' acquisitions within {} s put it: a pose edited by hand, or rig.json "
        "changed since the registration? run register again",
        a.module, a.counter, nearest_mm, apart, partners, kWindowS);
  }
  return "";
}

}  // namespace sewer3d
