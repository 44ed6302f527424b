// Gain evaluation of the 30 ring candidates on the 129 x 129 x 65 table top after one scan:
// exact, fast, and the OctoMap way (BENCHMARK.md).
#include <benchmark/benchmark.h>

#include "bench/fixtures.hpp"
#include "bench/octomap_gain.hpp"
#include "vantage/gain/exact.hpp"
#include "vantage/gain/fast.hpp"

namespace vantage::bench {
namespace {

GainConfig with_threads(const benchmark::State& state) {
  GainConfig config;
  config.num_threads = static_cast<int>(state.range(0));
  return config;
}

double total(const std::vector<ViewGain>& gains) {
  double sum = 0.0;
  for (const ViewGain& g : gains) sum += g.gain;
  return sum;
}

/// The 30 ring views of the table top after one scan, evaluated by `evaluate` with the argument's
/// thread count.
template <typename Evaluate>
void gain30(benchmark::State& state, Evaluate evaluate) {
  const World& world = table_top_after_one_scan();
  const GainConfig config = with_threads(state);
  double gain = 0.0;
  for (auto _ : state) gain = total(evaluate(world.grid, world.views, config));
  state.counters["views"] = static_cast<double>(world.views.size());
  state.counters["gain_bits"] = gain;
}

void BM_Gain30_Exact(benchmark::State& state) {
  gain30(state, [](const auto&... args) { return exact_view_gains(args...); });
}
BENCHMARK(BM_Gain30_Exact)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Gain30_Fast(benchmark::State& state) {
  gain30(state, [](const auto&... args) { return fast_view_gains(args...); });
}
BENCHMARK(BM_Gain30_Fast)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The snapshot alone (part of every fast and exact evaluation above).
void BM_GainMapSnapshot(benchmark::State& state) {
  const World& world = table_top_after_one_scan();
  for (auto _ : state)
    benchmark::DoNotOptimize(GainMap(world.grid, static_cast<int>(state.range(0))));
}
BENCHMARK(BM_GainMapSnapshot)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Gain30_OctoMap(benchmark::State& state) {
  const World& world = table_top_after_one_scan();
  static const std::unique_ptr<octomap::OcTree> tree = to_octree(world.grid);
  const GainConfig config = with_threads(state);
  OctoMapGains result;
  for (auto _ : state) {
    result = octomap_view_gains(*tree, world.grid.spec(), world.grid.params(), world.views, config);
  }
  state.counters["views"] = static_cast<double>(world.views.size());
  state.counters["gain_bits"] = total(result.gains);
  state.counters["rays"] = static_cast<double>(result.rays);
  state.counters["lookups"] = static_cast<double>(result.keys);
}
BENCHMARK(BM_Gain30_OctoMap)
    ->Arg(2)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
}  // namespace vantage::bench
