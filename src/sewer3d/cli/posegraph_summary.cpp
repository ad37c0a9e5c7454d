#include "sewer3d/cli/posegraph_summary.hpp"

#include <fmt/core.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include "sewer3d/core/check.hpp"

namespace sewer3d::cli {
namespace {

void PrintCertificate(const PoseGraphReport& r) {
  if (!r.certificate_applicable) {
    fmt::print("certificate not applicable: {}\n",
               r.certificate_reason.empty() ? "LM failed" : r.certificate_reason);
    return;
  }
  if (!std::isfinite(r.lower_bound)) {
    fmt::print("certificate failed: {}\n", r.certificate_reason);
    return;
  }
  fmt::print(
      "certificate lower bound {:.7g} (relaxation rank {}{}{}, {:.3f} s){}\n", r.lower_bound,
      r.relaxation_rank, r.relaxation_solved ? "" : ", not solved: bound is loose",
      r.dominated_relaxation ? fmt::format(", information lowered on {} edges", r.dominated_edges)
                             : "",
      r.certificate_seconds, r.certificate_improved ? "; its solution was lower and is taken" : "");
  fmt::print("            final cost is within {:.2g} % of the global optimum (relative gap){}\n",
             100.0 * std::max(0.0, r.RelativeGap()), r.RelativeGap() <= 1e-4 ? ": certified" : "");
}

}  // namespace

// Edges whose information matches their noise give a χ² (2 × cost) of about 6 each; the
// noisiest public benchmark (sphere_bignoise) has 342. Far above, edges or fixed nodes
// contradict each other and the optimum is a compromise no measurement supports.
void WarnOfDisagreement(const std::string& in, double final_cost, size_t edges) {
  constexpr double kMaxChi2PerEdge = 1e4;
  if (edges == 0) return;
  const double chi2 = 2.0 * final_cost / static_cast<double>(edges);
  if (!(chi2 > kMaxChi2PerEdge)) return;
  std::fflush(stdout);
  fmt::print(stderr,
             "sewer3d: warning: {}: the edges contradict each other or the fixed nodes: χ² "
             "{:.3g} per edge at the optimum (about 6 when the information matches the noise)\n",
             in, chi2);
}

void WarnOfUnitMismatch(const std::string& in, const PoseGraph& graph) {
  constexpr double kFactor = 100.0;
  std::vector<double> ratios;
  for (const PoseEdge& e : graph.edges()) {
    const double poses = (graph.node(e.to).translation - graph.node(e.from).translation).norm();
    const double edge = e.a_from_b.translation.norm();
    if (poses > 0.0 && edge > 0.0) ratios.push_back(edge / poses);
  }
  if (ratios.size() < 2) return;
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  const double ratio = ratios[ratios.size() / 2];
  if (ratio < kFactor && ratio > 1.0 / kFactor) return;
  std::fflush(stdout);
  fmt::print(stderr,
             "sewer3d: warning: {}: the edges' translations are {:.3g} times the distances of "
             "the poses they join (median): one in metres, the other in millimetres? The result "
             "follows the edges\n",
             in, ratio);
}

void WarnOfSwappedEdges(const std::string& in, const PoseGraph& graph) {
  constexpr double kFactor = 100.0;
  const double as_written = GraphCost(graph), inverted = GraphCostEdgesInverted(graph);
  // Far from the poses either way (no initial guess, or a noisy one): nothing to tell.
  if (!(as_written > kFactor * inverted) ||
      !(as_written > static_cast<double>(graph.edges().size())))
    return;
  std::fflush(stdout);
  fmt::print(stderr,
             "sewer3d: warning: {}: the edges fit the file's poses far better the other way round "
             "(cost {:.4g} as written, {:.4g} with each edge inverted): from and to swapped "
             "(another tool's convention)? The result follows the edges as written\n",
             in, as_written, inverted);
}

void WarnOfQuaternionOrder(const std::string& in, const PoseGraph& graph) {
  // Every edge nearly a half turn: a near-identity rotation written w, x, y, z (w first) and
  // read x, y, z, w has its 1 in the x slot and a small w (|w| < 0.2: within 23° of 180°).
  // Odometry edges turn a little; a whole graph of half turns is a misread.
  if (graph.edges().size() < 2) return;
  for (const PoseEdge& e : graph.edges()) {
    if (std::abs(e.a_from_b.rotation.w()) >= 0.2) return;
  }
  std::fflush(stdout);
  fmt::print(stderr,
             "sewer3d: warning: {}: every edge turns by nearly 180° (|qw| < 0.2): quaternions "
             "written w, x, y, z? g2o's order is x, y, z, w; the result follows the file\n",
             in);
}

void WarnOfOutlierEdge(const std::string& in, const PoseGraph& optimised) {
  const std::optional<OutlierEdge> outlier = FindOutlierEdge(optimised);
  if (!outlier) return;
  const PoseEdge& e = optimised.edges()[outlier->index];
  std::fflush(stdout);
  fmt::print(stderr,
             "sewer3d: warning: {}: edge {} {} has χ² {:.3g} at the optimum, {:.3g} times the "
             "median edge's: the other edges contradict it (in other units, or a wrong match?) "
             "and the poses around it are a compromise\n",
             in, e.from, e.to, outlier->chi2, outlier->chi2 / std::max(outlier->median_chi2, 1.0));
}

std::string WhyNotWritten(const PoseGraphReport& r) {
  if (!r.usable)
    return fmt::format("optimisation did not give a usable solution ({})", r.termination);
  if (r.unanchored_nodes == 0) return "";
  return fmt::format(
      "{} of {} nodes have no chain of edges to a fixed node, so their poses are not determined",
      r.unanchored_nodes, r.nodes);
}

void CheckCertifiable(const std::string& in, std::size_t poses) {
  // The certificate's time grows with about the cube of the poses (2 cores: 1 s at 2 000,
  // 12 s at 5 000, 160 s at 10 000): beyond, it would run for hours.
  constexpr std::size_t kMaxCertifiedPoses = 10000;
  if (poses <= kMaxCertifiedPoses) return;
  throw InvalidValue("--certify", fmt::format("{} has {} poses; the certificate is computed for "
                                              "graphs of up to {} (its time grows with about the "
                                              "cube of the size)",
                                              in, poses, kMaxCertifiedPoses));
}

void PrintPoseGraphReport(const PoseGraphReport& r, const PoseGraphOptions& options) {
  fmt::print("init        {} (initial cost {:.7g}, {:.3f} s)\n", r.init_used, r.initial_cost,
             r.init_seconds);
  fmt::print("final cost  {:.7g} after {} iterations, {:.3f} s, {} thread(s)\n", r.final_cost,
             r.iterations, r.solve_seconds, options.num_threads);
  fmt::print("termination {}\n", r.termination);
  // Poses without a chain of edges to a fixed node are whatever the file said.
  fmt::print("usable      {}\n", r.usable && r.unanchored_nodes == 0 ? "yes" : "no");
  if (options.certify) PrintCertificate(r);
}

}  // namespace sewer3d::cli
