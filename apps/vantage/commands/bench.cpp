/// `vantage bench`: the paper's experiments as resumable, shardable sweeps, and `merge` to join
/// shards.

#include "vantage/experiment/bench.hpp"

#include <fmt/core.h>

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "commands/commands.hpp"
#include "commands/options.hpp"
#include "shell.hpp"
#include "vantage/experiment/decision_cost.hpp"
#include "vantage/experiment/exploration.hpp"
#include "vantage/experiment/results.hpp"
#include "vantage/gain/ray_model.hpp"
#include "vantage/sim/generate.hpp"
#include "vantage/sim/object_scene.hpp"
#include "vantage/sim/scene.hpp"
#include "vantage/util/memory.hpp"
#include "vantage/util/work.hpp"

namespace vantage::cli {
namespace {

namespace fs = std::filesystem;

struct BenchOptions {
  std::vector<std::string> scenes = {"tabletop-1", "tabletop-2", "tabletop-3", "tabletop-4"};
  /// The default planner beside the paper's three (§5.1).
  std::vector<std::string> methods = {to_string(default_planner_method(ViewTask::kObjects, true)),
                                      "probabilistic", "greedy", "random"};
  std::string alphas;      ///< empty: each method's own, as explore runs it
  std::string objectives;  ///< empty: each method's own
  int trials = 10;
  int scans = 10;
  std::uint64_t seed = 1;
  int jobs = 1;
  std::string shard = "0/1";
  std::string out = "results/bench-tabletop";
  std::string kind = "tabletop";  ///< which experiment: tabletop or office
  bool plots = true;
  bool revisit = false;
  bool project_stops = true;  ///< office: unreachable frontier centroids move into their region
  PlanningOptions planning;
  MappingOptions mapping;
  CandidateOptions candidates;               ///< tabletop only
  std::uint64_t max_memory = 0;              // 0: what the machine has available
  double max_work = kDefaultMaxWorkSeconds;  ///< [s] of a decision's estimated work
  int generated = 0;  ///< tabletop: generated piles, instead of --scenes unless given
  int objects = sim::PileConfig{}.objects;
  std::uint64_t generated_seed = 1;
  bool scenes_given = false;  ///< --scenes was on the command line
  double max_setup = 3600.0;  ///< [s] of estimated set-up before the first trial (issue 53)
};

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

void run(const BenchOptions& o) {
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

void add_sweep_command(CLI::App& bench, const std::string& name, const std::string& description,
                       const std::string& trials_help, const std::shared_ptr<BenchOptions>& o) {
  CLI::App* cmd = bench.add_subcommand(name, description);
  if (o->kind == "objects") {
    cmd->add_option("--objects", o->scenes,
                    "objects, each on its own view sphere: mesh files (.ply, .obj, .off, .stl) "
                    "or built-in models")
        ->delimiter(',')
        ->capture_default_str();
  } else {
    cmd->add_option("--scenes", o->scenes, "scenes")->delimiter(',')->capture_default_str();
  }
  cmd->add_option("--methods", o->methods,
                  "methods (planner methods, and greedy-oracle: table tops)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--alphas", o->alphas,
                  fmt::format("a settings of the probabilistic and survival methods, a,b,... (a "
                              "number in (0, 1] or auto; survival's auto has its own grid and "
                              "prior, {})",
                              kSurvivalAlpha))
      ->default_str(o->alphas.empty() ? "each method's own, as explore: auto for survival, the "
                                        "paper's a for probabilistic"
                                      : o->alphas);
  cmd->add_option("--objectives", o->objectives,
                  "what the probabilistic and survival methods rank by, one trial set each: "
                  "bits,cells")
      ->default_str("each method's own: cells for survival, bits for probabilistic");
  cmd->add_option(o->kind == "objects" ? "--starts,--trials" : "--trials", o->trials, trials_help)
      ->check(whole_in(1, kMaxScans))
      ->capture_default_str();
  cmd->add_option(
         "--scans,-n", o->scans,
         o->kind == "office" ? "stops per trial (a 360-degree sweep each)" : "scans per trial")
      ->check(whole_in(1, kMaxScans))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "base seed")->check(seed_value())->capture_default_str();
  cmd->add_option("--jobs", o->jobs, "trials run in parallel")
      ->check(whole_in(1, kMaxThreads))
      ->capture_default_str();
  cmd->add_option("--shard", o->shard, "run slice I of N (0-based), e.g. 2/8")
      ->capture_default_str();
  cmd->add_option("--out,-o", o->out, "sweep folder; rerunning resumes it")->capture_default_str();
  cmd->add_flag("!--no-plots", o->plots, "skip plots and summary");
  add_memory_option(*cmd, o->max_memory);
  add_work_option(*cmd, o->max_work);
  cmd->add_option("--max-setup", o->max_setup,
                  "[s] of estimated work before the first trial (the table tops' surface "
                  "yardsticks), past which the sweep is refused before it starts")
      ->check(number_in(0.0, 1e9, /*open_low=*/true))
      ->capture_default_str();
  if (o->kind == "objects") {
    cmd->add_flag("--revisit", o->revisit,
                  "views already taken stay candidates (the paper's loop taken literally)");
    o->candidates.add_to(*cmd);
  } else if (o->kind == "tabletop") {
    cmd->add_flag("--revisit", o->revisit,
                  "views already taken stay candidates (the paper's loop taken literally)");
    cmd->add_option("--generated", o->generated,
                    "also bench this many generated piles (vantage scene generate), seeds "
                    "--generated-seed, +1, ...; without --scenes, only them")
        ->check(whole_in(0, kMaxScans))
        ->capture_default_str();
    cmd->add_option("--objects", o->objects, "objects in each generated pile")
        ->check(whole_in(1, sim::kMaxPileObjects))
        ->capture_default_str();
    cmd->add_option("--generated-seed", o->generated_seed, "seed of the first generated pile")
        ->check(seed_value())
        ->capture_default_str();
    o->candidates.add_to(*cmd);
  } else {
    cmd->add_flag("!--no-stop-projection", o->project_stops, kNoStopProjectionHelp);
  }
  o->planning.add_to(*cmd);
  o->mapping.add_to(*cmd);
  // A sweep runs trials in parallel; one thread per trial unless told otherwise.
  cmd->get_option("--threads")->default_val(1);
  // NOTE: a sweep takes lists; the single-valued options explore and plan take would be accepted
  // and ignored, so they are hidden and refused.
  constexpr std::array<std::pair<const char*, const char*>, 3> kLists = {
      {{"--method", "--methods"}, {"--alpha", "--alphas"}, {"--objective", "--objectives"}}};
  for (const auto& [single, list] : kLists) cmd->get_option(single)->group("");
  cmd->callback([o, cmd, kLists] {
    for (const auto& [single, list] : kLists) {
      if (cmd->count(single) > 0) {
        throw UsageError(fmt::format(
            "{} is explore's and plan's: a sweep takes {} (a comma-separated list)", single, list));
      }
    }
    if (o->kind == "tabletop" && o->generated == 0) {
      for (const char* option : {"--objects", "--generated-seed"}) {
        if (cmd->count(option) > 0) {
          throw UsageError(
              fmt::format("{} shapes generated piles: give --generated N too", option));
        }
      }
    }
    o->scenes_given = o->kind != "objects" && cmd->count("--scenes") > 0;
    run(*o);
  });
}

}  // namespace

void add_bench_command(CLI::App& app) {
  CLI::App* bench = app.add_subcommand("bench", "The paper's experiments as sweeps");
  bench->require_subcommand(1);

  auto tabletop = std::make_shared<BenchOptions>();
  add_sweep_command(*bench, "tabletop",
                    "Table-top sweep: scenes x methods x trials (the paper's Figs. 10 and 11)",
                    "trials per scene and method; trial i starts from ring position i", tabletop);

  auto objects = std::make_shared<BenchOptions>();
  objects->kind = "objects";
  objects->scenes = {"bunny", "dragon", "teapot"};
  objects->methods.emplace_back(kGreedyOracleName);
  objects->trials = 5;
  objects->out = "results/bench-objects";
  add_sweep_command(*bench, "objects",
                    "Object sweep, the field's protocol (docs/objects.md): single objects x "
                    "methods x starts on a view sphere of 32 views",
                    "starts per object and method; start i is the i-th of the sphere's views "
                    "spread apart",
                    objects);

  const BenchConfig paper = office_bench_config();
  auto office = std::make_shared<BenchOptions>();
  office->kind = "office";
  office->scenes = paper.scenes;
  office->methods.clear();
  for (const PlannerMethod m : paper.methods) office->methods.emplace_back(to_string(m));
  office->alphas = fmt::format("{},{}", paper.alphas[0].label(), paper.alphas[1].label());
  office->trials = paper.trials;
  office->scans = paper.exploration.scans;
  office->out = "results/bench-office";
  add_sweep_command(
      *bench, "office",
      "Office sweep: offices x methods x starts, frontier stops (the paper's Figs. 15 and 16)",
      "trials per scene and method; trial i starts from the scene's start pose i", office);

  auto dirs = std::make_shared<std::vector<std::string>>();
  auto out = std::make_shared<std::string>();
  auto plots = std::make_shared<bool>(true);
  CLI::App* merge = bench->add_subcommand("merge", "Join the trial files of shard folders");
  merge->add_option("dirs", *dirs, "sweep folders to join")->required();
  merge->add_option("--out,-o", *out, "folder to write (default: the first folder)");
  merge->add_flag("!--no-plots", *plots, "skip plots and summary");
  merge->callback([dirs, out, plots] {
    std::vector<fs::path> paths(dirs->begin(), dirs->end());
    // NOTE: a folder that is not there is said as such, not as a folder without sweep.json.
    for (const fs::path& dir : paths) {
      std::error_code error;
      if (!fs::is_directory(dir, error)) {
        throw std::runtime_error(
            fmt::format("bench merge: {}: {}", dir.string(),
                        fs::exists(dir, error) ? "is not a folder" : "no such folder"));
      }
    }
    const fs::path target = out->empty() ? paths.front() : fs::path(*out);
    merge_bench(paths, target);
    fmt::print("merged {} folder(s) into {}\n", paths.size(), (target / "scans.csv").string());
    // NOTE: the merged sweep is drawn as one run on one machine draws it.
    if (*plots) {
      std::fflush(stdout);
      run_plot_script("plot_bench.py", {target.string()});
      fmt::print(
          "plots and summary: {}/unobserved.png, prediction_error.png, summary.md, "
          "trials.csv\n",
          target.string());
    }
  });
}

}  // namespace vantage::cli
