// The field's seven metrics (issue 36, item 4): one metric's decision among the 187 hemisphere
// views of the issue-26 sweeps (radii 0.9, 1.1 and 1.3 m, 0.3 m apart, tabletop-4's target) on
// tabletop-4 after 1, 3 and 6 paper-mode scans, every view evaluated by the metric's own rays
// (`--evaluation auto`, as `vantage explore --method <metric>` runs it) and the best taken, or the
// decision as `vantage explore` takes it by default (the swept search's race of the metric's views
// on its coarser rays). Wall time on 2 threads (BENCHMARK.md, "The seven metrics at speed" and
// "The metrics raced").
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "vantage/gain/evaluators/metric_evaluator.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/map/integrate.hpp"
#include "vantage/planner/planner.hpp"
#include "vantage/sim/world.hpp"
#include "vantage/views/hemisphere.hpp"
#include "vantage/views/ring.hpp"

namespace vantage::bench {
namespace {

/// Scans from these start poses, in this order (as in the oracle tests).
constexpr int kScanOrder[] = {0, 5, 2, 7, 3, 8};

constexpr GainMethod kMetrics[] = {GainMethod::kOcclusionAware, GainMethod::kUnobservedVoxel,
                                   GainMethod::kRearSideVoxel,  GainMethod::kRearSideEntropy,
                                   GainMethod::kProximityCount, GainMethod::kAverageEntropy,
                                   GainMethod::kAreaFactor,     GainMethod::kSurface};

struct HemisphereState {
  OccupancyGrid grid;
  std::vector<Frustum> views;
};

/// tabletop-4 after `scans` scans and its 187 hemisphere views; built once per process.
const HemisphereState& hemisphere_state(int scans) {
  static std::map<int, HemisphereState> states;
  if (const auto it = states.find(scans); it != states.end()) return it->second;
  const sim::World world(sim::load_scene("tabletop-4"));
  const sim::Scene& scene = world.scene();
  HemisphereConfig hemisphere;
  hemisphere.center = scene.mount.target;
  hemisphere.radii = {0.9, 1.1, 1.3};
  hemisphere.spacing = 0.3;
  HemisphereState state{OccupancyGrid(scene.grid),
                        make_views(hemisphere_poses(hemisphere), scene.fov())};
  for (int k = 0; k < scans; ++k) {
    const sim::SimulatedScan scan =
        world.scan(scene.start_poses[static_cast<std::size_t>(kScanOrder[k])], 1000 + k);
    integrate_scan(state.grid, Scan{scan.points_world(), scan.view()}, IntegrationConfig{});
  }
  return states.emplace(scans, std::move(state)).first->second;
}

/// Arguments: metric (0-6 in the order of docs/model.md, M1-M7; 7 the surface model, with the
/// rates its fit left after 8 hemisphere scans of tabletop-3), scans (1, 3 or 6), walk (0 the
/// reference, cell by cell; 1 the jumping walk metric_view_gains takes, every view; 2 the default
/// decision, plan_next_view's swept search).
void BM_MetricDecision187(benchmark::State& bench) {
  const GainMethod method = kMetrics[bench.range(0)];
  const HemisphereState& s = hemisphere_state(static_cast<int>(bench.range(1)));
  const int walk = static_cast<int>(bench.range(2));
  GainConfig config;
  config.method = method;
  config.num_threads = 2;
  std::vector<Candidate> cands;
  for (const Frustum& view : s.views) cands.push_back({view, 0.0});
  PlannerConfig planner;
  planner.method = PlannerMethod{method};
  planner.gain.num_threads = 2;
  config.surface_rates = planner.gain.surface_rates = {0.634, 0.157, 0.064, 0.035, 0.0038};
  std::size_t best = 0, evaluated = s.views.size();
  double gain = 0.0;
  for (auto _ : bench) {
    if (walk == 2) {
      const Plan plan = plan_next_view(s.grid, cands, planner);
      best = plan.best;
      evaluated = plan.evaluated;
      gain = plan.gains[best].gain;
      continue;
    }
    const std::vector<ViewGain> gains =
        walk == 0
            ? metric_view_gains_reference(GainMap(s.grid, config.num_threads), s.views, config)
            : metric_view_gains(s.grid, s.views, config);
    const auto it = std::max_element(gains.begin(), gains.end(),
                                     [](const auto& a, const auto& b) { return a.gain < b.gain; });
    best = static_cast<std::size_t>(it - gains.begin());
    gain = it->gain;
  }
  bench.SetLabel(std::string(to_string(method)));
  bench.counters["views"] = static_cast<double>(s.views.size());
  bench.counters["chosen"] = static_cast<double>(best);
  bench.counters["exact"] = static_cast<double>(evaluated);  // views evaluated at full pitch
  bench.counters["gain"] = gain;
}
BENCHMARK(BM_MetricDecision187)
    ->ArgsProduct({{0, 1, 2, 3, 4, 5, 6, 7}, {1, 3, 6}, {0, 1, 2}})
    ->ArgNames({"metric", "scans", "walk"})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

/// The set-up of the surface model's decision alone (docs/decision.md, "The set-up of a metric
/// decision"): `MetricEvaluator`'s constructor on tabletop-4 after 1, 3 or 6 scans, on 1 or 2
/// threads.
void BM_MetricSetUp(benchmark::State& bench) {
  const HemisphereState& s = hemisphere_state(static_cast<int>(bench.range(0)));
  GainConfig config;
  config.method = GainMethod::kSurface;
  config.num_threads = static_cast<int>(bench.range(1));
  config.surface_rates = {0.634, 0.157, 0.064, 0.035, 0.0038};
  std::size_t creditable = 0;
  for (auto _ : bench) {
    const MetricEvaluator evaluator(s.grid, config);
    creditable = evaluator.creditable().size();
  }
  bench.counters["creditable"] = static_cast<double>(creditable);
}
BENCHMARK(BM_MetricSetUp)
    ->ArgsProduct({{1, 3, 6}, {1, 2}})
    ->ArgNames({"scans", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

}  // namespace
}  // namespace vantage::bench
