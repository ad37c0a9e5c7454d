#pragma once
/// \file
/// What `sewer3d posegraph` prints of an optimisation (cli/cmd_posegraph.cpp): the report's
/// lines, the certificate, the warnings, and why a result is not written.

#include <cstddef>
#include <string>

#include "sewer3d/posegraph/solver.hpp"

namespace sewer3d::cli {

/// Throws InvalidValue for --certify on a graph too large for the certificate.
void CheckCertifiable(const std::string& in, std::size_t poses);

/// init, final cost, termination, usable, and the certificate where asked for (stdout).
void PrintPoseGraphReport(const PoseGraphReport& r, const PoseGraphOptions& options);

/// A warning (stderr) when the edges contradict each other or the fixed nodes.
void WarnOfDisagreement(const std::string& in, double final_cost, std::size_t edges);

/// A warning (stderr) when the edges' translations and the file's poses differ by a factor of
/// 100 or more (median over the edges whose poses lie apart): one of them in metres, the other
/// in millimetres. Graphs whose poses all sit at one place (no initial guess) are left alone.
void WarnOfUnitMismatch(const std::string& in, const PoseGraph& graph);

/// A warning (stderr) when the edges, each inverted, fit the file's poses 100 times better
/// than as written (GraphCostEdgesInverted): from and to swapped.
void WarnOfSwappedEdges(const std::string& in, const PoseGraph& graph);

/// A warning (stderr) when every edge's quaternion has |w| < 0.2 (nearly a half turn each):
/// the file written w first.
void WarnOfQuaternionOrder(const std::string& in, const PoseGraph& graph);

/// Warns (stderr) of the optimised graph's edge whose χ² stands out from the others'
/// (FindOutlierEdge): one measurement the rest contradict.
void WarnOfOutlierEdge(const std::string& in, const PoseGraph& optimised);

/// Why the optimised poses are no result, or "": the optimisation failed, or some poses have
/// no chain of edges to a fixed node and are whatever the file said.
std::string WhyNotWritten(const PoseGraphReport& r);

}  // namespace sewer3d::cli
