// Perfect-submap search: time to reach arrays of growing size (6-row torus, the shipped shape),
// and the codebook lookup rate.
#include <benchmark/benchmark.h>

#include "sewer3d/pattern/codebook.hpp"
#include "sewer3d/pattern/default_pattern.hpp"
#include "sewer3d/pattern/submap_search.hpp"

namespace sewer3d {
namespace {

void BM_SearchTorus6(benchmark::State& state) {
  SubmapSearchOptions options = DefaultPatternSearchOptions();
  options.cols = static_cast<int>(state.range(0));
  std::int64_t moves = 0, reached = 0, runs = 0;
  for (auto _ : state) {
    options.seed = static_cast<std::uint64_t>(++runs);
    const auto result = SearchPerfectSubmap(options);
    moves += result.moves;
    reached += result.reached;
  }
  state.counters["moves"] = benchmark::Counter(double(moves) / runs);
  state.counters["reached"] = benchmark::Counter(double(reached) / runs);
}
BENCHMARK(BM_SearchTorus6)->Arg(100)->Arg(160)->Arg(200)->Unit(benchmark::kMillisecond);

void BM_CodebookDecodeWithError(benchmark::State& state) {
  const BinaryArray array = DefaultPatternArray();
  const Codebook codebook(array, PatternConstraints{});
  std::vector<std::uint64_t> words;
  for (int c = 0; c < array.cols; ++c) words.push_back(TiledWindowCode(array, 1, c, 6) ^ (1u << 7));
  for (auto _ : state) {
    int found = 0;
    for (auto w : words) found += codebook.Decode(w).has_value();
    benchmark::DoNotOptimize(found);
  }
  state.SetItemsProcessed(state.iterations() * words.size());
}
BENCHMARK(BM_CodebookDecodeWithError);

}  // namespace
}  // namespace sewer3d
