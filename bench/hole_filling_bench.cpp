// MRF/ICM hole filling (§4.4) on the paper's 129 x 129 x 65 table-top grid, in the state it runs
// on during integration: right after the hits of one 640 x 480 scan, before unknown-space
// estimation (so nearly every cell is still unobserved and may change). Target: under 100 ms.

#include <benchmark/benchmark.h>

#include "synthetic_tabletop.hpp"
#include "vantage/map/hole_filling.hpp"

namespace vantage {
namespace {

OccupancyGrid after_hits_of_one_scan() {
  const synthetic::Scene scene = synthetic::table_top();
  OccupancyGrid grid(synthetic::grid_spec());
  const Frustum view = synthetic::ring_views()[1];
  for (const Eigen::Vector3d& p : synthetic::scan(scene, view, 640, 480)) {
    if (const auto cell = grid.spec().find(p)) grid.hit(grid.spec().linear(*cell));
  }
  return grid;
}

void BM_HoleFillingAfterOneScan(benchmark::State& state) {
  const OccupancyGrid before = after_hits_of_one_scan();
  std::size_t filled = 0;
  int sweeps = 0;
  for (auto _ : state) {
    state.PauseTiming();
    OccupancyGrid grid = before;
    state.ResumeTiming();
    const HoleFillingResult result = fill_holes(grid, HoleFillingConfig{});
    filled = result.filled.size();
    sweeps = result.sweeps;
    benchmark::DoNotOptimize(grid);
  }
  state.counters["filled"] = static_cast<double>(filled);
  state.counters["sweeps"] = sweeps;
}
BENCHMARK(BM_HoleFillingAfterOneScan)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

}  // namespace
}  // namespace vantage
