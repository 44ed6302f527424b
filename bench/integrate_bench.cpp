// Integrating one 640 x 480 scan at 1/128 m: ours (endpoint mode) against
// OcTree::insertPointCloud (BENCHMARK.md).
#include <benchmark/benchmark.h>
#include <octomap/OcTree.h>

#include <chrono>

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

}  // namespace
}  // namespace vantage::bench
