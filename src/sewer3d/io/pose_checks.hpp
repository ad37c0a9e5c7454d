#pragma once
/// \file
/// Whether a workspace's registered poses (registration/poses.csv) can be one run's: checks of
/// the poses against each other, the run's odometry and its rig, which the model stage makes
/// before it builds anything on them. A file edited by hand, written in other units or
/// conventions, or left from another run would otherwise bend the model without a word. Each
/// returns why the poses cannot be used, or "".

#include <string>
#include <vector>

#include "sewer3d/io/registration_io.hpp"
#include "sewer3d/run/odometry.hpp"
#include "sewer3d/run/rig.hpp"

namespace sewer3d {

/// Why `rows` cannot be one run's poses, or "": two acquisitions of a module, next to each other
/// in time, whose cameras lie farther apart than a crawler moves (0.5 m plus 2 m/s of their time
/// difference): an edited poses.csv or a registration gone wrong, which would stretch the model
/// over the gap.
std::string PoseJumpProblem(std::vector<RegistrationPoseRow> rows);

/// Why `rows` disagree with the run's odometry (`readings`, sorted by time), or "": a module
/// whose camera travels between its first and last acquisition under a fifth or over five times
/// the odometry's distance over the same time, when that is 20 mm or more (poses in metres, or
/// of another run). Slipping wheels and a slack cable stay far within the factor.
std::string PoseTravelProblem(std::vector<RegistrationPoseRow> rows,
                              const std::vector<OdometryReading>& readings);

/// Why `rows` move against the run's odometry (`readings`, sorted by time), or "": a module
/// whose camera, over steps of 20 mm or more of odometry, moves along the carrier axis (the
/// rig's, in the camera's frame at the step's start) less than half the odometry's distance
/// forward in most of its steps: poses written as camera_from_world, or with the axis negated.
/// Bends leave each step's direction as it is; modules the rig lacks are left to other checks.
std::string PoseDirectionProblem(std::vector<RegistrationPoseRow> rows,
                                 const std::vector<OdometryReading>& readings, const Rig& rig);

/// Why `rows` disagree with the rig, or "": an acquisition whose carrier pose (its camera's
/// through the rig) lies more than 25 mm plus the odometry's distance between them from where
/// most (and at least two) other modules' acquisitions within 0.25 s of it put the carrier: a
/// pose edited by hand, or rig.json changed since the registration. The registration holds the
/// modules to the rig within a few millimetres; without odometry over both times the carrier
/// may have moved 2 m/s of their time difference.
std::string PoseRigProblem(const std::vector<RegistrationPoseRow>& rows,
                           const std::vector<OdometryReading>& readings, const Rig& rig);

}  // namespace sewer3d
