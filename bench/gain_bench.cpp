// Google Benchmark kernels of the core: exact gain of ring candidates on a table-top sized grid.
#include <benchmark/benchmark.h>

#include "vantage/gain/view_gain.hpp"
#include "vantage/views/ring.hpp"

namespace vantage {
namespace {

OccupancyGrid table_top_grid() {
  return OccupancyGrid(GridSpec::centered({0, 0, 0.25}, 1.0 / 128.0, {129, 129, 65}));
}

void BM_ExactGainOneView(benchmark::State& state) {
  const OccupancyGrid grid = table_top_grid();
  RingConfig ring;
  ring.center = {0, 0, 0.1};
  ring.radius = 1.0;
  ring.height = 0.8;
  const auto views = make_views(ring_poses(ring), SensorFov{});
  GainConfig config;
  config.method = state.range(0) == 0 ? GainMethod::kProbabilistic : GainMethod::kGreedy;
  for (auto _ : state) {
    benchmark::DoNotOptimize(exact_view_gain(grid, views.front(), config));
  }
}
BENCHMARK(BM_ExactGainOneView)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vantage
