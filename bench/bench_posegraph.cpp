// Pose-graph optimisation on the public benchmark graphs: wall time of chordal initialisation
// and of Levenberg-Marquardt, for 1 and 2 threads. Counters: final cost, iterations. Then the
// certificate (Riemannian staircase) from the LM optimum: lower bound, rank, relative gap.
#include <benchmark/benchmark.h>

#include <string>

#include "sewer3d/io/g2o_io.hpp"
#include "sewer3d/posegraph/certificate.hpp"
#include "sewer3d/posegraph/solver.hpp"

namespace sewer3d {
namespace {

const char* const kFiles[] = {"tinyGrid3D.g2o", "smallGrid3D.g2o", "parking-garage.g2o",
                              "sphere_bignoise_vertex3.g2o"};

void BM_PoseGraph(benchmark::State& state) {
  const std::string file = kFiles[state.range(0)];
  const PoseGraph original = ReadG2o(std::string(SEWER3D_DATA_DIR) + "/posegraph/" + file);
  PoseGraphOptions options;
  options.init = state.range(2) ? PoseGraphInit::kChordal : PoseGraphInit::kGiven;
  options.num_threads = static_cast<int>(state.range(1));
  PoseGraphReport report;
  for (auto _ : state) {
    state.PauseTiming();
    PoseGraph graph = original;
    state.ResumeTiming();
    report = OptimisePoseGraph(graph, options);
  }
  state.SetLabel(file + (state.range(2) ? " chordal" : " odometry"));
  state.counters["final_cost"] = report.final_cost;
  state.counters["iterations"] = report.iterations;
  state.counters["init_s"] = report.init_seconds;
}
BENCHMARK(BM_PoseGraph)
    ->ArgsProduct({{0, 1, 2, 3}, {1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_PoseGraphCertificate(benchmark::State& state) {
  const std::string file = kFiles[state.range(0)];
  PoseGraph optimum = ReadG2o(std::string(SEWER3D_DATA_DIR) + "/posegraph/" + file);
  PoseGraphOptions options;
  options.num_threads = 2;
  const double final_cost = OptimisePoseGraph(optimum, options).final_cost;
  CertificateReport report;
  for (auto _ : state) report = CertifyPoseGraph(optimum, CertificateOptions());
  state.SetLabel(file);
  state.counters["lower_bound"] = report.lower_bound;
  state.counters["rank"] = report.rank;
  state.counters["iterations"] = report.iterations;
  state.counters["relative_gap"] = (final_cost - report.lower_bound) / final_cost;
}
BENCHMARK(BM_PoseGraphCertificate)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace sewer3d
