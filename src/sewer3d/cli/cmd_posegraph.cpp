// `sewer3d posegraph`: optimises a g2o pose graph and prints the report.

#include <fmt/core.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <thread>

#include "sewer3d/cli/argument_checks.hpp"
#include "sewer3d/cli/command.hpp"
#include "sewer3d/cli/posegraph_summary.hpp"
#include "sewer3d/core/check.hpp"
#include "sewer3d/io/atomic_file.hpp"
#include "sewer3d/io/g2o_io.hpp"
#include "sewer3d/io/input_file.hpp"
#include "sewer3d/posegraph/solver.hpp"

namespace sewer3d::cli {
namespace {

/// "huber:0.5" -> 0.5; nullopt when malformed.
std::optional<double> ParseRobust(const std::string& text) {
  constexpr std::string_view kPrefix = "huber:";
  if (!text.starts_with(kPrefix)) return std::nullopt;
  const std::string number = text.substr(kPrefix.size());
  char* end = nullptr;
  const double delta = std::strtod(number.c_str(), &end);
  // Below 1e-3 sigma the loss's gradient vanishes and the solver stops where it starts.
  if (number.empty() || *end != '\0' || !(delta >= 1e-3) || !(delta <= 1e6)) return std::nullopt;
  return delta;
}

}  // namespace

Command AddPoseGraphCommand(CLI::App& app) {
  struct Args {
    std::string in, out, init = "auto", robust;
    PoseGraphOptions options;
  };
  auto args = std::make_shared<Args>();
  args->options.num_threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  CLI::App* sub =
      app.add_subcommand("posegraph", "Optimise a g2o pose graph (Ceres LM, chordal init)");
  sub->add_option("--in", args->in, "Input graph (g2o VERTEX_SE3:QUAT / EDGE_SE3:QUAT)")
      ->required();
  sub->add_option("--out", args->out, "Optimised graph to write (g2o)")
      ->required()
      ->check(FileNameEnding(".g2o", "the optimised graph is written as g2o text"));
  sub->add_option("--init", args->init, "Start: the file's poses (odometry), chordal, or auto")
      ->capture_default_str()
      ->check(CLI::IsMember({"odometry", "chordal", "auto"}));
  sub->add_option("--robust", args->robust,
                  "Robust loss on every edge, e.g. huber:1.0 (sigma units)")
      ->check(CLI::Validator(
          [](std::string& s) {
            return ParseRobust(s)
                       ? std::string()
                       : "expected huber:DELTA with DELTA 1e-3..1e6 (sigma units), got " + s;
          },
          "huber:DELTA"));
  sub->add_option("--max-iterations", args->options.max_iterations,
                  "Levenberg-Marquardt iterations")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  sub->add_option("--threads", args->options.num_threads, "Threads for Ceres")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  sub->add_flag("--certify", args->options.certify,
                "Bound the global optimum (semidefinite relaxation, Riemannian staircase); "
                "takes its solution where it is lower");
  return {sub, [args] {
            PoseGraphOptions options = args->options;
            options.init = args->init == "odometry"  ? PoseGraphInit::kGiven
                           : args->init == "chordal" ? PoseGraphInit::kChordal
                                                     : PoseGraphInit::kAuto;
            if (!args->robust.empty()) options.huber_delta = *ParseRobust(args->robust);
            CheckFileNotInRunOrWorkspace(args->out, "--out");
            CheckOutputFile(args->out);
            CheckNotAnInput(args->out, args->in, "--in");
            PoseGraph graph = ReadG2o(args->in);
            WarnOfUnitMismatch(args->in, graph);
            WarnOfSwappedEdges(args->in, graph);
            WarnOfQuaternionOrder(args->in, graph);
            if (options.certify) CheckCertifiable(args->in, graph.nodes().size());
            fmt::print("{}: {} poses, {} edges, cost at its poses {:.7g}\n", args->in,
                       graph.nodes().size(), graph.edges().size(), GraphCost(graph));
            std::fflush(stdout);
            const PoseGraphReport r = OptimisePoseGraph(graph, options);
            PrintPoseGraphReport(r, options);
            if (const std::string why = WhyNotWritten(r); !why.empty()) {
              std::fflush(stdout);  // a file at --out would pass for a result
              fmt::print(stderr, "sewer3d: error: {}: {}; {} not written\n", args->in, why,
                         args->out);
              return 1;
            }
            if (r.termination.rfind("NO_CONVERGENCE", 0) == 0) {  // usable, not the optimum
              std::fflush(stdout);
              fmt::print(stderr,
                         "sewer3d: warning: {}: stopped at --max-iterations {} before converging: "
                         "the poses written are better than the start, not the optimum\n",
                         args->in, options.max_iterations);
            }
            WarnOfDisagreement(args->in, r.final_cost, graph.edges().size());
            WarnOfOutlierEdge(args->in, graph);
            WriteG2o(args->out, graph);
            fmt::print("wrote {}\n", args->out);
            return 0;
          }};
}

}  // namespace sewer3d::cli
