/// `vantage bench`'s sweep run (bench.hpp): the options as a BenchConfig, the memory, work and
/// set-up it will take checked before any trial, the trials, the plots.

#include <fmt/core.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands/bench.hpp"
#include "shell.hpp"
#include "vantage/experiment/bench.hpp"
#include "vantage/experiment/decision_cost.hpp"
#include "vantage/experiment/exploration.hpp"
#include "vantage/experiment/results.hpp"
#include "vantage/gain/ray_model.hpp"
#include "vantage/sim/object_scene.hpp"
#include "vantage/sim/scene.hpp"
#include "vantage/util/memory.hpp"

namespace vantage::cli {
namespace {

namespace fs = std::filesystem;

/// The comma-separated items of a list option.
std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> items;
  std::size_t from = 0;
  for (;;) {
    const std::size_t comma = text.find(',', from);
    items.push_back(text.substr(from, comma - from));
    if (comma == std::string::npos) return items;
    from = comma + 1;
  }
}

void parse_shard(const std::string& text, BenchConfig& config) {
  const auto slash = text.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    std::size_t used = 0;
    config.shard_index = std::stoi(text.substr(0, slash), &used);
    if (used != slash) throw std::invalid_argument("index");
    config.shard_count = std::stoi(text.substr(slash + 1), &used);
    if (used != text.size() - slash - 1) throw std::invalid_argument("count");
  } catch (const std::exception&) {
    throw std::invalid_argument(fmt::format("--shard '{}' is not of the form I/N", text));
  }
}

BenchConfig bench_config(const BenchOptions& o) {
  BenchConfig config;
  config.scenes = o.scenes;
  // NOTE: --generated replaces the default scenes; named ones given with it are benched too.
  if (o.generated > 0 && !o.scenes_given) config.scenes.clear();
  config.generated = o.generated;
  config.pile.objects = o.objects;
  config.pile.seed = o.generated_seed;
  config.methods.clear();
  // NOTE: the greedy oracle is the experiment layer's (it knows the world), not a planner method.
  std::vector<std::string> planner_methods;
  for (const std::string& m : o.methods) {
    if (m == kGreedyOracleName) {
      config.greedy_oracle = true;
    } else {
      planner_methods.push_back(m);
      config.methods.push_back(parse_planner_method(m));
    }
  }
  // NOTE: auto starts from the literal a of the sweep's kind (§5.1, §5.2).
  const double prior = o.kind == "office" ? kOfficeAlpha : kTableTopAlpha;
  config.paper_alpha = prior;
  config.alphas.clear();
  for (const std::string& a :
       o.alphas.empty() ? std::vector<std::string>{} : split_list(o.alphas)) {
    try {
      config.alphas.push_back(parse_alpha_setting(a, prior));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(fmt::format("--alphas: {}", e.what()));
    }
  }
  config.objectives.clear();
  for (const std::string& name :
       o.objectives.empty() ? std::vector<std::string>{} : split_list(o.objectives)) {
    config.objectives.push_back(parse_gain_objective(name));
  }
  config.trials = o.trials;
  // NOTE: the methods are the trials'; each is checked against the shared settings (a --search
  // that does not serve one is refused before any trial), and the first stands in.
  PlanningOptions planning = o.planning;
  for (const std::string& m : planner_methods) {
    planning.method = m;
    (void)planning.planner_config();
  }
  planning.method = planner_methods.empty() ? std::string(to_string(PlannerMethod::kGreedy))
                                            : planner_methods.front();
  config.exploration.planner = planning.planner_config();
  config.exploration.mapper.integration.mode = parse_integration_mode(o.mapping.integration);
  config.exploration.mapper.integration.hole_filling.enabled = o.mapping.hole_filling;
  config.exploration.mapper.integration.num_threads = o.planning.threads;
  config.exploration.mapper.register_scans = o.mapping.icp;
  config.exploration.mapper.segment_table = o.mapping.segmentation;
  config.exploration.scans = o.scans;
  config.exploration.seed = o.seed;
  config.exploration.revisit = o.revisit;
  config.exploration.planner.greedy_reference = o.greedy_reference;
  config.exploration.office.project_stops = o.project_stops;
  config.objects = o.candidates.object_protocol();
  // NOTE: a sweep's scenes share one kind: objects, or table tops (generated piles included).
  o.candidates.apply(config.exploration,
                     o.kind == "objects" ? sim::SceneKind::kObject : sim::SceneKind::kTableTop);
  config.exploration.budget = work_budget(o.max_work, o.max_memory);
  config.jobs = o.jobs;
  parse_shard(o.shard, config);
  config.validate();
  return config;
}

/// Refuses a sweep whose set-up before its first trial is estimated past --max-setup (issue 53:
/// `--generated 100000` printed nothing for minutes): every table top's surface yardstick, each
/// generated pile's as the first one's (`scenes`' last).
void check_setup(const BenchOptions& o, const BenchConfig& config,
                 const std::vector<sim::Scene>& scenes) {
  double rays = 0.0;
  std::size_t table_tops = 0;
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    if (scenes[i].kind != sim::SceneKind::kTableTop) continue;
    const std::size_t copies = config.generated > 0 && i + 1 == scenes.size()
                                   ? static_cast<std::size_t>(config.generated)
                                   : 1;
    table_tops += copies;
    rays += static_cast<double>(copies) *
            surface_truth_rays(scenes[i], run_candidates(scenes[i], config.exploration).size());
  }
  const double seconds = rays * kNanosecondsPerSimulatedRay * 1e-9;
  if (seconds <= o.max_setup) return;
  throw UsageError(fmt::format(
      "the sweep's set-up before its first trial, the surface yardstick's noise-free scans of {} "
      "table tops ({} simulated rays at {} ns), is estimated at {}, more than --max-setup {} "
      "allows: raise it, or bench fewer scenes",
      table_tops, significant(rays), kNanosecondsPerSimulatedRay, describe_seconds(seconds),
      describe_seconds(o.max_setup)));
}

}  // namespace

void run_sweep(const BenchOptions& o) {
  const BenchConfig config = from_options([&] { return bench_config(o); });

  // NOTE: --jobs trials at once, each with its own grid; the largest scene decides.
  std::vector<sim::Scene> scenes;
  for (const std::string& name : config.scenes) {
    scenes.push_back(sim::load_scene(name, config.objects));
  }
  if (config.generated > 0) scenes.push_back(sim::pile_scene(bench_piles(config).front()));
  std::uint64_t cells = 0;
  for (const sim::Scene& scene : scenes) {
    cells = std::max<std::uint64_t>(cells, scene.grid.num_cells());
  }
  check_memory({cells, grid_bytes_per_cell(o.planning.threads), kFixedRunBytes,
                static_cast<std::uint64_t>(o.jobs)},
               o.max_memory, "the sweep's grids");
  // Every method's decision on every scene's candidates, against the work budget (and each
  // trial's decisions on their maps, ExplorationConfig::budget).
  for (const sim::Scene& scene : scenes) {
    for (const PlannerMethod method : config.methods) {
      ExplorationConfig exploration = config.exploration;
      exploration.planner.method = method;
      exploration.planner.objective = natural_objective(method);
      if (const auto cost = estimate_run_decision(scene, exploration)) {
        check_decision_budget(*cost, config.exploration.budget,
                              scene.grid.num_cells() * static_cast<std::uint64_t>(o.jobs),
                              o.planning.threads);
      }
    }
  }
  check_setup(o, config, scenes);
  const std::size_t total = bench_trials(config).size();
  fmt::print("bench: {} trials in all, shard {}, {} job(s), into {}\n", total, o.shard, o.jobs,
             o.out);
  const std::size_t ran = run_bench(o.out, config, [](const TrialEvent& e) {
    fmt::print(
        "[{:3}/{}] {:<48} {}\n", e.done, e.total, e.spec.key(),
        e.skipped ? std::string("done before, skipped") : fmt::format("{:.1f} s", e.seconds));
    std::fflush(stdout);
  });
  fmt::print("ran {} trial(s); {}\n", ran, (fs::path(o.out) / "scans.csv").string());
  // NOTE: an object's 32 views prove their fewest covers in seconds: beside every object sweep.
  if (o.kind == "objects" && config.shard_count == 1) {
    run_plot_script("set_cover.py", {o.out});
    fmt::print("the fewest views to each level: {}/set_cover.csv\n", o.out);
  }
  if (o.plots && config.shard_count == 1) {
    run_plot_script("plot_bench.py", {o.out});
    fmt::print(
        "plots and summary: {}/unobserved.png, {}prediction_error.png, summary.md, trials.csv\n",
        o.out, o.kind == "office" ? "unobserved_by_travel.png, " : "");
  }
}

}  // namespace vantage::cli
