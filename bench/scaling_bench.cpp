// How the exact evaluation grows with the grid (129^2, 257^2, 513^2 x 65 cells at 1/128 m), the
// number of candidates (10, 30, 100, 300) and the threads (1, 2) (BENCHMARK.md).
#include <benchmark/benchmark.h>

#include "bench/fixtures.hpp"
#include "vantage/gain/evaluators/exact.hpp"

namespace vantage::bench {
namespace {

void BM_GainScaling(benchmark::State& state) {
  const int cells = static_cast<int>(state.range(0));
  const auto n = static_cast<std::size_t>(state.range(1));
  const World& world = scaled_world(cells);
  const std::span<const Frustum> views(world.views.data(), n);
  GainConfig config;
  config.num_threads = static_cast<int>(state.range(2));
  for (auto _ : state) benchmark::DoNotOptimize(exact_view_gains(world.grid, views, config));
  state.counters["cells"] = static_cast<double>(world.grid.size());
  state.counters["views"] = static_cast<double>(n);
}
// Args: grid cells along x and y, candidates, threads.
BENCHMARK(BM_GainScaling)
    ->ArgsProduct({{129, 257, 513}, {10, 30, 100, 300}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
}  // namespace vantage::bench
