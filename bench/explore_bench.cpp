// Every decision of a default run, one at a time (issue 52: every decision within its budget, not
// the median): `vantage explore --scene tabletop-4 --threads 2` with no other option, its ring and
// its default planner (latombe+surface, the surface rates fitted online), played up to the scan
// asked for; then the decision for the next scan (Exploration::propose, the one step() takes)
// timed again and again on that state. scans:k is the decision that chooses scan k + 1, as
// `scripts/bench-defaults.sh` counts it for scan k + 1. Wall time on 2 threads (BENCHMARK.md,
// issue 52's section).
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <utility>

#include "vantage/experiment/exploration.hpp"
#include "vantage/experiment/planning_settings.hpp"
#include "vantage/sim/scene.hpp"

namespace vantage::bench {
namespace {

constexpr int kThreads = 2;

/// A default run of tabletop-4 after `scans` scans; built once per process. The run keeps
/// references to the scene, the config and the mapper, so they live beside it.
struct PlayedRun {
  sim::Scene scene;
  ExplorationConfig config;
  std::unique_ptr<Mapper> mapper;
  std::unique_ptr<Exploration> run;
};

ExplorationConfig default_config(const sim::Scene& scene) {
  PlanningSettings planning;
  planning.threads = kThreads;
  ExplorationConfig config;
  config.planner = planning.planner_config();
  config.mapper = default_mapper_config(scene);
  config.mapper.integration.num_threads = kThreads;
  config.mapper.registration.num_threads = kThreads;
  config.mapper.map.num_threads = kThreads;
  config.scans = 14;
  return config;
}

Exploration& played(int scans) {
  static std::map<int, PlayedRun> runs;
  if (const auto it = runs.find(scans); it != runs.end()) return *it->second.run;
  PlayedRun& p = runs[scans];
  p.scene = sim::load_scene("tabletop-4");
  p.config = default_config(p.scene);
  p.mapper = std::make_unique<Mapper>(p.scene.grid, p.config.mapper);
  p.run = std::make_unique<Exploration>(p.scene, p.config, *p.mapper);
  for (int k = 0; k < scans; ++k) p.run->step();
  return *p.run;
}

/// Argument: the scans taken before the decision (1-7: the decisions for scans 2-8).
void BM_DefaultRingDecision(benchmark::State& bench) {
  Exploration& run = played(static_cast<int>(bench.range(0)));
  int view = -1;
  double plan_ms = 0.0;  // the decision as the run records it (seconds.plan)
  for (auto _ : bench) {
    const ViewProposal proposal = run.propose();
    view = proposal.view;
    plan_ms = 1e3 * proposal.seconds;
  }
  bench.counters["chosen"] = view;
  bench.counters["plan_ms"] = plan_ms;
}
BENCHMARK(BM_DefaultRingDecision)
    ->DenseRange(1, 7)
    ->ArgName("scans")
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

}  // namespace
}  // namespace vantage::bench
