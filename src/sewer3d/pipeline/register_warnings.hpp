#pragma once
/// \file
/// What the registration stage warns of, in words that name the run's file: the odometry's
/// problems (CaptureRun::odometry_findings, readings outside the images' times, jumps, a stuck
/// counter) and pairs of modules whose registrations contradict rig.json
/// (register/module_agreement.hpp), or the odometry along the pipe.

#include <string>
#include <vector>

#include "sewer3d/register/initial_poses.hpp"
#include "sewer3d/register/module_agreement.hpp"
#include "sewer3d/register/prior_edges.hpp"
#include "sewer3d/run/capture_run.hpp"

namespace sewer3d {

/// One line per problem of the run's odometry.csv, naming its lines and the acquisitions they
/// concern.
std::vector<std::string> OdometryWarnings(const CaptureRun& run,
                                          const std::vector<AcquisitionNode>& nodes);

/// One line per pair of modules whose registrations the gate rejected (nearly) all of
/// (Disagrees), naming rig.json, the two modules and how far apart the rejected
/// registrations put them; a module in two such pairs is named as the likely one.
std::vector<std::string> RigWarnings(const CaptureRun& run,
                                     const std::vector<ModulePairAgreement>& pairs);

/// A line when the pipe the first instant's walls show (`walls`, when valid) is no wider than
/// rig.json's carrier: the carrier's diameter is wrong (units?); "" otherwise.
std::string CarrierWarning(const CaptureRun& run, const CarrierOffsetEstimate& walls);

/// A line when `edges` (between node indices) leave the `nodes` in more than one connected
/// part: their poses relative to each other are then the initial guess's (`--edges` naming
/// too few kinds); "" otherwise.
std::string GraphWarning(int nodes, const std::vector<RegistrationEdge>& edges);

/// A line when the gate rejected (nearly) all registrations along the pipe (Disagrees on
/// AlongAgreement): odometry.csv in other units or scale; "" otherwise.
std::string AlongWarning(const CaptureRun& run, const ModulePairAgreement& along);

/// A line when the gate rejected at least half of the odometry edges (of at least 2): along
/// the whole run the images put the acquisitions elsewhere than the counter's distances say,
/// odometry.csv in other units or scale (a counter that slips rejects a few edges, where it
/// slipped, and is not named); "" otherwise.
std::string OdometryRejectedWarning(const CaptureRun& run, const EdgeTypeStatistics& odometry);

/// A line when the odometry edges, kept by the fusion, disagree with the solution far beyond
/// their noise (median χ² over 100 of at least 2 edges; about 6 when the odometry is right):
/// a counter whose scale is wrong (a factor 2 measured 4296); "" otherwise.
std::string OdometryFitWarning(const CaptureRun& run, const EdgeTypeStatistics& odometry);

}  // namespace sewer3d
