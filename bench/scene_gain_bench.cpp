// Gain evaluation of the 30 ring candidates on the built-in table tops (vantage::sim) after 1, 3
// and 6 paper-mode scans: the map states of the gain's scene test
// (tests/gain/gain_scenes_test.cpp), so each evaluation's cost can be followed as a table
// top is explored (BENCHMARK.md, "The built-in scenes").
#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "vantage/gain/view_gain.hpp"
#include "vantage/map/integrate.hpp"
#include "vantage/sim/world.hpp"
#include "vantage/views/ring.hpp"

namespace vantage::bench {
namespace {

/// Scans from these start poses, in this order (as in the oracle test).
constexpr int kScanOrder[] = {0, 5, 2, 7, 3, 8};

struct SceneState {
  OccupancyGrid grid;
  std::vector<Frustum> views;
};

/// `tabletop-<scene>` after `scans` scans; built once per process.
const SceneState& scene_state(int scene, int scans) {
  static std::map<std::pair<int, int>, SceneState> states;
  const auto key = std::make_pair(scene, scans);
  if (const auto it = states.find(key); it != states.end()) return it->second;
  const sim::World world(sim::load_scene("tabletop-" + std::to_string(scene)));
  const sim::Scene& spec = world.scene();
  SceneState state{OccupancyGrid(spec.grid), make_views(spec.candidate_poses(), spec.fov())};
  for (int k = 0; k < scans; ++k) {
    const sim::SimulatedScan scan =
        world.scan(spec.start_poses[static_cast<std::size_t>(kScanOrder[k])], 1000 + k);
    integrate_scan(state.grid, Scan{scan.points_world(), scan.view()}, IntegrationConfig{});
  }
  return states.emplace(key, std::move(state)).first->second;
}

/// Arguments: scene 1..4, scans 1, 3 or 6.
void BM_SceneGain30(benchmark::State& state) {
  const SceneState& s =
      scene_state(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  GainConfig config;
  config.num_threads = 1;
  double gain = 0.0;
  for (auto _ : state) {
    gain = 0.0;
    for (const ViewGain& g : evaluate_views(s.grid, s.views, config)) gain += g.gain;
  }
  state.counters["gain_bits"] = gain;
}
BENCHMARK(BM_SceneGain30)
    ->ArgsProduct({{1, 2, 3, 4}, {1, 3, 6}})
    ->ArgNames({"tabletop", "scans"})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vantage::bench
