// Integrating one 640 x 480 scan at 1/128 m: ours (endpoint mode) against
// OcTree::insertPointCloud (BENCHMARK.md).
#include <benchmark/benchmark.h>
#include <octomap/OcTree.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "bench/fixtures.hpp"
#include "vantage/map/integrate.hpp"

namespace vantage::bench {
namespace {

/// The scan, all of it (arg 0) or only its points inside the grid (arg 1).
PointCloud scan_points(const World& world, bool inside_only) {
  if (!inside_only) return world.last_scan;
  PointCloud inside;
  for (const Eigen::Vector3d& p : world.last_scan) {
    if (world.grid.spec().contains(p)) inside.push_back(p);
  }
  return inside;
}

void BM_Integrate_Ours(benchmark::State& state) {
  const World& world = table_top_after_one_scan();
  const Scan scan{scan_points(world, state.range(1) != 0), world.last_view};
  IntegrationConfig config;
  config.mode = IntegrationMode::kEndpoint;
  config.num_threads = static_cast<int>(state.range(0));
  OccupancyGrid grid(world.grid.spec());
  for (auto _ : state) {
    grid.reset();  // an empty map each time, as for OctoMap below; not timed
    const auto start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(integrate_scan(grid, scan, config));
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  state.counters["points"] = static_cast<double>(scan.points_world.size());
  // NOTE: each cell is updated once, from unobserved, so the cells now known are the writes
  // that changed a class, each a census update (BM_GridWrites).
  const CellCounts counts = grid.counts();
  state.counters["class_changes"] = static_cast<double>(counts.free + counts.occupied);
}
// Args: threads, inside-only.
BENCHMARK(BM_Integrate_Ours)
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({1, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime();

void BM_Integrate_OctoMap(benchmark::State& state) {
  const World& world = table_top_after_one_scan();
  octomap::Pointcloud cloud;
  for (const Eigen::Vector3d& p : scan_points(world, state.range(0) != 0)) {
    cloud.push_back(static_cast<float>(p.x()), static_cast<float>(p.y()),
                    static_cast<float>(p.z()));
  }
  const Eigen::Vector3d o = world.last_view.origin();
  const octomap::point3d origin(static_cast<float>(o.x()), static_cast<float>(o.y()),
                                static_cast<float>(o.z()));
  const OccupancyParams params;
  for (auto _ : state) {
    octomap::OcTree tree(world.grid.spec().resolution);  // an empty map each time; not timed
    tree.setProbHit(params.p_hit);
    tree.setProbMiss(params.p_miss);
    tree.setClampingThresMin(params.p_min);
    tree.setClampingThresMax(params.p_max);
    const auto start = std::chrono::steady_clock::now();
    tree.insertPointCloud(cloud, origin);
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    benchmark::DoNotOptimize(tree.size());
  }
  state.counters["points"] = static_cast<double>(cloud.size());
}
// Arg: inside-only. Debian's OctoMap is built without OpenMP: one thread.
BENCHMARK(BM_Integrate_OctoMap)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseManualTime();

/// What the grid's census and packed classes cost a write that changes a cell's class
/// (docs/decision.md, "The swept search", item 6): arg 0, a miss on every cell of the table
/// top's 129 x 129 x 65 grid, all unobserved, so every write moves a cell to free; arg 1, the
/// same clamped log-odds additions on a bare float array, what a write cost before.
void BM_GridWrites(benchmark::State& state) {
  const GridSpec spec = GridSpec::centered({0, 0, 0}, 0.01, {129, 129, 65});
  for (auto _ : state) {
    state.PauseTiming();
    OccupancyGrid grid(spec);
    std::vector<float> bare(grid.size(), 0.0f);
    const auto miss = static_cast<float>(logit(grid.params().p_miss));
    const auto lo = static_cast<float>(logit(grid.params().p_min));
    state.ResumeTiming();
    if (state.range(0) == 0) {
      for (std::size_t i = 0; i < grid.size(); ++i) grid.miss(i);
    } else {
      for (float& l : bare) l = std::max(lo, l + miss);
    }
    benchmark::DoNotOptimize(grid.log_odds().data());
    benchmark::DoNotOptimize(bare.data());
  }
  state.counters["writes"] = static_cast<double>(spec.num_cells());
}
BENCHMARK(BM_GridWrites)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vantage::bench
