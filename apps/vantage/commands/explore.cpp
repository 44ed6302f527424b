/// `vantage explore`: the main job. Explores a simulated scene scan by scan with a chosen method,
/// shows live progress, and leaves a results folder with the data and the pictures.

#include <fmt/chrono.h>
#include <fmt/core.h>
#include <fmt/ranges.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>

#include "commands/commands.hpp"
#include "commands/options.hpp"
#include "shell.hpp"
#include "vantage/experiment/bench.hpp"
#include "vantage/experiment/exploration.hpp"
#include "vantage/experiment/results.hpp"
#include "vantage/gain/ray_model.hpp"
#include "vantage/io/atomic_file.hpp"
#include "vantage/io/octomap_io.hpp"
#include "vantage/planner/search.hpp"
#include "vantage/sim/scene.hpp"
#include "vantage/sim/world.hpp"
#include "vantage/util/memory.hpp"

namespace vantage::cli {
namespace {

namespace fs = std::filesystem;

struct ExploreOptions {
  std::string scene = "tabletop-3";
  std::string object;  ///< a mesh file or built-in model: a single object on its view sphere
  PlanningOptions planning;
  MappingOptions mapping;
  CandidateOptions candidates;
  int scans = 10;
  double min_gain = 0.0;
  bool revisit = false;
  bool greedy_reference = false;
  bool project_stops = true;
  int start = 0;
  std::uint64_t seed = 1;
  std::string out;
  bool plots = true;
  bool quiet = false;
  std::uint64_t max_memory = 0;              // 0: what the machine has available
  double max_work = kDefaultMaxWorkSeconds;  // [s] of a decision's estimated work
};

fs::path default_out(const ExploreOptions& o, PlannerMethod method) {
  const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  const std::string scene = o.object.empty() ? o.scene : fs::path(o.object).stem().string();
  return fs::path("results") / fmt::format("explore-{}-{}-{:%Y%m%d-%H%M%S}", scene,
                                           to_string(method), fmt::localtime(now));
}

void print_scan(const ScanRecord& r, int total, bool ranks_by_bits) {
  // NOTE: in cells, the unit of the actual gain beside it (docs/model.md, "Bits are not cells");
  // a run that ranks by bits shows them first, the number it chose by (run.json: units, objective).
  const std::string bits =
      ranks_by_bits ? fmt::format("{:7.0f} bits ", r.predicted_gain.value_or(0.0)) : "";
  const std::string predicted =
      r.predicted_cells
          ? fmt::format("{}{:7.0f} cells {:<16}", bits, *r.predicted_cells,
                        r.greedy_predicted_gain
                            ? fmt::format("(greedy {:>7.0f})", *r.greedy_predicted_gain)
                            : std::string())
          : fmt::format("{:>7} {:>{}}", "-", "", 21 + bits.size());
  const double seconds = r.seconds.scan + r.seconds.register_scan + r.seconds.segment +
                         r.seconds.integrate + r.seconds.plan;
  const std::string travel =
      r.goal || r.travel > 0.0
          ? fmt::format("  travel {:5.2f} m{}", r.travel, r.fallback ? " (fallback)" : "")
          : std::string();
  fmt::print(
      "scan {:2}/{}  view {:2}  predicted {}  actual {:7}  unobserved {:8}  "
      "coverage {:5.1f}%{}  icp {:4.1f}->{:4.1f} mm{}  {:5.2f} s{}\n",
      r.scan, total, r.view, predicted, r.actual_gain, r.unobserved, 100.0 * r.coverage,
      r.surface_coverage ? fmt::format("  surface {:5.1f}%", 100.0 * *r.surface_coverage) : "",
      1e3 * r.pose_error_before, 1e3 * r.pose_error_after, travel, seconds,
      r.reregistered.empty()
          ? std::string()
          : fmt::format("  (registered scan {} again)", fmt::join(r.reregistered, ", ")));
  std::fflush(stdout);
}

/// The run's settings, and the a it was given.
struct ExploreSettings {
  ExplorationConfig config;
  AlphaSetting alpha;
};

/// The run's settings from the options and the scene.
ExploreSettings explore_settings(const ExploreOptions& o, const sim::Scene& scene) {
  const bool office = scene.kind == sim::SceneKind::kOffice;
  // The paper's a for the scene's kind (§5.1, §5.2); the method's own a (default_alpha) when
  // --alpha is not given, and the prior of --alpha auto.
  const double paper = office ? kOfficeAlpha : kTableTopAlpha;
  ExplorationConfig config;
  // NOTE: the greedy oracle is the experiment layer's (it knows the world), not a planner method:
  // greedy's settings stand in for it (docs/yardstick.md).
  PlanningOptions planning = o.planning;
  planning.task = office ? ViewTask::kExploration : ViewTask::kObjects;
  config.greedy_oracle = planning.method == kGreedyOracleName;
  if (config.greedy_oracle) planning.method = std::string(to_string(PlannerMethod::kGreedy));
  config.planner = planning.planner_config(paper);
  const double literal = default_alpha(config.planner.method, paper);
  const bool survival = uses_survival_reading(config.planner.method);
  // NOTE: the survival reading is fitted online unless told an a: the configuration the sweeps
  // show best (RESULTS.md); --method probabilistic is the paper's literal one.
  const AlphaSetting alpha = o.planning.alpha.empty()
                                 ? default_alpha_setting(config.planner.method, paper)
                                 : o.planning.alpha_setting(literal);
  config.auto_alpha = alpha.automatic;
  if (survival) config.observability = survival_fit_config();
  config.observability.prior = alpha.value;
  config.mapper = o.mapping.mapper_config(scene);
  config.mapper.integration.num_threads = o.planning.threads;
  config.mapper.registration.num_threads = o.planning.threads;
  config.mapper.map.num_threads = o.planning.threads;
  config.scans = o.scans;
  config.min_gain = o.min_gain;
  config.revisit = o.revisit;
  config.planner.greedy_reference = o.greedy_reference;
  config.office.project_stops = o.project_stops;
  config.start = o.start;
  config.seed = o.seed;
  o.candidates.apply(config, scene.kind);
  from_options([&] { config.validate(); });
  return {config, alpha};
}

/// Refuses before any work a grid too large for memory or one whose map cannot be written, and
/// a decision or yardstick past the work budget (which it sets).
void check_before_work(const ExploreOptions& o, const sim::Scene& scene,
                       ExplorationConfig& config) {
  const std::string grid_name =
      fmt::format("the grid of scene {} ({} x {} x {} cells)", scene.name, scene.grid.dims.x(),
                  scene.grid.dims.y(), scene.grid.dims.z());
  check_memory({scene.grid.num_cells(), grid_bytes_per_cell(o.planning.threads), kFixedRunBytes},
               o.max_memory, grid_name);
  require_octomap_range(scene.grid, grid_name);
  config.budget = work_budget(o.max_work, o.max_memory);
  if (const auto cost = estimate_run_decision(scene, config)) {
    check_decision_budget(*cost, config.budget, scene.grid.num_cells(), o.planning.threads);
    // NOTE: a table top's run scans every candidate for the yardstick before its first decision.
    check_surface_truth(scene, run_candidates(scene, config).size(), config.budget);
  }
}

void run(const ExploreOptions& o) {
  const sim::Scene scene = o.object.empty()
                               ? sim::load_scene(o.scene, o.candidates.object_protocol())
                               : sim::single_object_scene(o.object, o.candidates.object_protocol());
  ExploreSettings settings = explore_settings(o, scene);
  ExplorationConfig& config = settings.config;
  const AlphaSetting& alpha = settings.alpha;

  const fs::path out = o.out.empty() ? default_out(o, config.planner.method) : fs::path(o.out);
  if (fs::exists(out) && !fs::is_empty(out)) {
    throw std::invalid_argument(fmt::format("--out {} exists and is not empty", out.string()));
  }
  check_before_work(o, scene, config);
  if (!o.quiet) {
    fmt::print(
        "exploring {} with {} ({} evaluation, {} search{}), {} scans from start {}, "
        "seed {}\n",
        scene.name, config.greedy_oracle ? o.planning.method : to_string(config.planner.method),
        o.planning.evaluation, resolve_decider(config.planner).name(),
        has_observability(config.planner.method)
            ? fmt::format(", a = {}, ranking by {}", alpha.label(),
                          to_string(config.planner.objective))
            : "",
        o.scans, o.start, o.seed);
  }
  // NOTE: an object's yardstick (its views' true hit sets) is kept with the run, so that the
  // fewest views to each level are proven beside it (scripts/set_cover.py: set_cover.csv).
  std::optional<SurfaceTruth> truth;
  if (scene.kind == sim::SceneKind::kObject) {
    const sim::World world(scene, sim::WorldConfig{o.planning.threads});
    truth = compute_surface_truth(world, run_candidates(scene, config), config.coverage_tolerance,
                                  o.planning.threads);
  }
  Mapper mapper(scene.grid, config.mapper);
  const ExplorationResult result =
      explore(scene, config, mapper,
              o.quiet ? ScanCallback{} : ScanCallback([&](const ScanRecord& r, int total) {
                print_scan(r, total, gain_units(config.planner).score == "bits");
              }),
              truth ? &*truth : nullptr);

  write_folder_atomically(out, [&](const fs::path& dir) {
    write_run_files(dir, scene, config, result, mapper);
    if (truth) {
      write_yardstick_file(dir / kYardstickFolder / (scene.name + ".json"), scene, config, *truth);
      run_plot_script("set_cover.py", {dir.string()});
    }
    if (o.plots) run_plot_script("plot_run.py", {dir.string()});
  });
  const ScanRecord& last = result.scans.back();
  fmt::print(
      "{}: {} scans, {} unobserved cells left, coverage {:.1f}% of {} observable surface "
      "cells\nresults: {}\n",
      result.stop_reason, result.scans.size(), last.unobserved, 100.0 * last.coverage,
      result.observable_cells, out.string());
}

}  // namespace

void add_explore_command(CLI::App& app) {
  auto o = std::make_shared<ExploreOptions>();
  CLI::App* cmd = app.add_subcommand(
      "explore", "Explore a simulated scene scan by scan, choosing each next view (the main job)");
  CLI::Option* scene =
      cmd->add_option("--scene,-s", o->scene,
                      "built-in scene name, scene YAML file, or a mesh file (.ply, .obj, .off, "
                      ".stl) as a single object")
          ->capture_default_str();
  cmd->add_option("--object", o->object,
                  "a single object on its view sphere, the field's protocol (docs/objects.md): a "
                  "mesh file (.ply, .obj, .off, .stl) or a built-in model (bunny, dragon, teapot)")
      ->excludes(scene);
  o->planning.add_to(*cmd);
  cmd->get_option("--alpha")
      ->description(fmt::format(
          "observability parameter a, in (0, 1], or 'auto': fitted to the run's own predictions "
          "and outcomes (default: auto for survival; for probabilistic the paper's a, table top "
          "{}, office {})",
          kTableTopAlpha, kOfficeAlpha))
      ->default_str("");
  o->mapping.add_to(*cmd);
  o->candidates.add_to(*cmd);
  cmd->add_option("--scans,-n", o->scans, "number of scans to take (office: stops, a sweep each)")
      ->check(whole_in(1, kMaxScans))
      ->capture_default_str();
  cmd->add_option("--min-gain", o->min_gain,
                  "stop early when the best predicted gain falls below this [bits for "
                  "probabilistic, cells for the others]")
      ->check(number_in(0.0, 1e12))
      ->capture_default_str();
  cmd->add_flag(
      "--revisit", o->revisit,
      "table top: views already taken stay candidates (the paper's loop taken literally)");
  cmd->add_flag("--greedy-reference", o->greedy_reference, kGreedyReferenceHelp);
  cmd->add_flag("!--no-stop-projection", o->project_stops,
                fmt::format("office: {}", kNoStopProjectionHelp));
  cmd->add_option("--start", o->start, "start pose index of the scene")
      ->check(whole_in(0, kMaxIndex))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "seed of sensor noise, pose noise and random choice")
      ->check(seed_value())
      ->capture_default_str();
  cmd->add_option("--out,-o", o->out, "results folder (default: a fresh folder under results/)");
  cmd->add_flag("!--no-plots", o->plots, "skip the pictures");
  cmd->add_flag("--quiet,-q", o->quiet, "no per-scan progress");
  add_memory_option(*cmd, o->max_memory);
  add_work_option(*cmd, o->max_work);
  cmd->callback([o] { run(*o); });
}

}  // namespace vantage::cli
