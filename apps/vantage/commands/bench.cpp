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

#include "commands/bench.hpp"
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

/// The options of one kind of sweep: an object's view sphere, a table top's generated piles,
/// an office's stops.
void add_kind_options(CLI::App& cmd, BenchOptions& o) {
  if (o.kind == "objects") {
    cmd.add_flag("--revisit", o.revisit,
                 "views already taken stay candidates (the paper's loop taken literally)");
    o.candidates.add_to(cmd);
  } else if (o.kind == "tabletop") {
    cmd.add_flag("--revisit", o.revisit,
                 "views already taken stay candidates (the paper's loop taken literally)");
    cmd.add_option("--generated", o.generated,
                   "also bench this many generated piles (vantage scene generate), seeds "
                   "--generated-seed, +1, ...; without --scenes, only them")
        ->check(whole_in(0, kMaxScans))
        ->capture_default_str();
    cmd.add_option("--objects", o.objects, "objects in each generated pile")
        ->check(whole_in(1, sim::kMaxPileObjects))
        ->capture_default_str();
    cmd.add_option("--generated-seed", o.generated_seed, "seed of the first generated pile")
        ->check(seed_value())
        ->capture_default_str();
    o.candidates.add_to(cmd);
  } else {
    cmd.add_flag("!--no-stop-projection", o.project_stops, kNoStopProjectionHelp);
  }
}

// NOTE: a sweep takes lists; the single-valued options explore and plan take would be accepted
// and ignored, so they are hidden and refused.
constexpr std::array<std::pair<const char*, const char*>, 3> kLists = {
    {{"--method", "--methods"}, {"--alpha", "--alphas"}, {"--objective", "--objectives"}}};

/// Refuses what the sweep's command line gives but a sweep does not take, then runs it.
void check_and_run(CLI::App& cmd, BenchOptions& o) {
  for (const auto& [single, list] : kLists) {
    if (cmd.count(single) > 0) {
      throw UsageError(fmt::format(
          "{} is explore's and plan's: a sweep takes {} (a comma-separated list)", single, list));
    }
  }
  if (o.kind == "tabletop" && o.generated == 0) {
    for (const char* option : {"--objects", "--generated-seed"}) {
      if (cmd.count(option) > 0) {
        throw UsageError(fmt::format("{} shapes generated piles: give --generated N too", option));
      }
    }
  }
  o.scenes_given = o.kind != "objects" && cmd.count("--scenes") > 0;
  run_sweep(o);
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
  cmd->add_flag("--greedy-reference", o->greedy_reference, kGreedyReferenceHelp);
  add_memory_option(*cmd, o->max_memory);
  add_work_option(*cmd, o->max_work);
  cmd->add_option("--max-setup", o->max_setup,
                  "[s] of estimated work before the first trial (the table tops' surface "
                  "yardsticks), past which the sweep is refused before it starts")
      ->check(number_in(0.0, 1e9, /*open_low=*/true))
      ->capture_default_str();
  add_kind_options(*cmd, *o);
  o->planning.add_to(*cmd);
  o->mapping.add_to(*cmd);
  // A sweep runs trials in parallel; one thread per trial unless told otherwise.
  cmd->get_option("--threads")->default_val(1);
  for (const auto& [single, list] : kLists) cmd->get_option(single)->group("");
  cmd->callback([o, cmd] { check_and_run(*cmd, *o); });
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
