// Gain evaluation of the 30 ring candidates on the 129 x 129 x 65 table top after one scan:
// exact and the OctoMap way; and the paper's model's decision among them (BENCHMARK.md).
#include <benchmark/benchmark.h>

#include "bench/fixtures.hpp"
#include "bench/octomap_gain.hpp"
#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/planner/choose.hpp"
#include "vantage/planner/planner.hpp"

namespace vantage::bench {
namespace {

GainConfig with_threads(const benchmark::State& state) {
  GainConfig config;
  config.num_threads = static_cast<int>(state.range(0));
  return config;
}

/// The views' sum of one ViewGain member: `gain` [bits] or `targets` [cells].
template <typename Member>
double sum_of(const std::vector<ViewGain>& gains, Member ViewGain::*member) {
  double sum = 0.0;
  for (const ViewGain& g : gains) sum += static_cast<double>(g.*member);
  return sum;
}

/// The 30 ring views of the table top after one scan, evaluated by `evaluate` with the argument's
/// thread count.
template <typename Evaluate>
void gain30(benchmark::State& state, Evaluate evaluate) {
  const World& world = table_top_after_one_scan();
  const GainConfig config = with_threads(state);
  std::vector<ViewGain> gains;
  for (auto _ : state) gains = evaluate(world.grid, world.views, config);
  state.counters["views"] = static_cast<double>(world.views.size());
  state.counters["gain_bits"] = sum_of(gains, &ViewGain::gain);
  state.counters["targets"] = sum_of(gains, &ViewGain::targets);
}

void BM_Gain30_Exact(benchmark::State& state) {
  gain30(state, [](const auto&... args) { return exact_view_gains(args...); });
}
BENCHMARK(BM_Gain30_Exact)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The paper's model's decision over the same 30 views, by the expected cells seen (E, ViewGain::
// cells): the swept search, which races the views on the model's exact per-target v_M
// (docs/decision.md, "The paper's model"). `decision_ms` is the decision's own time (Plan::seconds,
// without the chosen view's full prediction after it), the figure to set against
// BM_Gain30_OctoMap, which evaluates every view; `same_choice` is 1 when it chose the view the
// exact evaluation of every view ranks first.
void BM_Gain30_Decision(benchmark::State& state) {
  const World& world = table_top_after_one_scan();
  static const std::size_t exact_best = [&] {
    const std::vector<ViewGain> exact = exact_view_gains(world.grid, world.views, GainConfig{});
    std::vector<double> cells;
    for (const ViewGain& g : exact) cells.push_back(g.cells);
    return choose_best(cells);
  }();
  std::vector<Candidate> candidates;
  for (const Frustum& view : world.views) candidates.push_back(Candidate{view});
  PlannerConfig config;
  config.method = PlannerMethod::kProbabilistic;
  config.objective = GainObjective::kCells;
  config.search = DecisionSearch::kSwept;
  config.gain = with_threads(state);
  Plan plan;
  for (auto _ : state) plan = plan_next_view(world.grid, candidates, config);
  state.counters["decision_ms"] = 1e3 * plan.seconds;
  state.counters["prediction_ms"] = 1e3 * plan.prediction_seconds;
  state.counters["chosen"] = static_cast<double>(plan.best);
  state.counters["same_choice"] = plan.best == exact_best ? 1.0 : 0.0;
  state.counters["raced"] = static_cast<double>(plan.evaluated);
}
BENCHMARK(BM_Gain30_Decision)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The snapshot alone (part of every exact evaluation above).
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
  state.counters["gain_bits"] = sum_of(result.gains, &ViewGain::gain);
  // NOTE: a cell is credited by the first pixel ray that reaches it before the ray is hidden, so
  // fewer cells than the exact evaluation's targets, each at a visible ray's value.
  state.counters["targets"] = sum_of(result.gains, &ViewGain::targets);
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
