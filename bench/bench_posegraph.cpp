// Pose-graph optimisation on the public benchmark graphs: wall time of chordal initialisation
// and of Levenberg-Marquardt, for 1 and 2 threads. Counters: final cost, iterations.
#include <benchmark/benchmark.h>

#include <string>

#include "sewer3d/io/g2o_io.hpp"
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

}  // namespace
}  // namespace sewer3d
