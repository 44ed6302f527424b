#include "commands/options.hpp"

#include <fmt/core.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <thread>

#include "shell.hpp"
#include "vantage/experiment/exploration.hpp"
#include "vantage/experiment/yardstick.hpp"
#include "vantage/planner/search.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/memory.hpp"
#include "vantage/views/candidate_sets.hpp"

namespace vantage::cli {

namespace {

/// A refused setting as the option that gave it: --name: message (exit 2).
template <typename F>
auto as_option(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const SettingError& e) {
    const std::string option = e.setting() == "planner" ? "" : fmt::format("--{}: ", e.setting());
    throw UsageError(option + e.what());
  }
}

std::vector<std::string> search_names() {
  std::vector<std::string> names;
  for (const SearchTraits& s : decision_searches()) names.emplace_back(s.search.name);
  return names;
}

}  // namespace

void PlanningOptions::add_to(CLI::App& cmd, bool search_option) {
  cmd.add_option("--method,-m", method,
                 "probabilistic, survival (the paper's model under the survival reading of its "
                 "visibility, docs/model.md), greedy, random, latombe, yamauchi, sequence "
                 "(survival's views planned past the next scan and toured: --horizon, "
                 "--travel-weight; default 3 views, 0.1/m), or one of the field's metrics: "
                 "occlusion-aware, unobserved-voxel, rear-side-voxel, rear-side-entropy, "
                 "proximity-count, average-entropy, area-factor (docs/model.md); surface (the "
                 "unobserved cells the rays reach, each weighed by its chance to be the first "
                 "surface met, fitted online); a ranking of "
                 "another gain as RANKING+GAIN (latombe+survival); explore and bench "
                 "on a table top also take greedy-oracle (the view whose true hits add the most "
                 "surface, docs/yardstick.md)")
      ->default_str(
          "latombe+surface around a table top (surface when plan has no robot pose), survival "
          "exploring an office or from frontier candidates");
  cmd.add_option("--alpha,-a", alpha,
                 "observability parameter a of the probabilistic and survival methods, in (0, 1], "
                 "or 'auto': fitted to the run's own predictions and outcomes")
      ->default_str(
          fmt::format("survival {}, probabilistic the paper's {}", kSurvivalAlpha, kTableTopAlpha));
  cmd.add_option("--objective", objective,
                 "what the probabilistic and survival methods rank by: bits (the information "
                 "gain, eq. 1) or cells (the expected number of unobserved cells seen)")
      ->default_str("the method's own: cells for survival, bits for probabilistic");
  cmd.add_option("--evaluation", evaluation,
                 "the metrics' ray pitch: auto (every third ray along each image axis) or exact "
                 "(every ray); the other methods always evaluate exactly")
      ->capture_default_str();
  if (search_option) {
    std::string help =
        "how the candidates are searched (docs/decision.md); by default the first of these that "
        "serves the method:";
    for (const SearchTraits& s : decision_searches()) {
      help += fmt::format(" {} ({});", s.search.name, s.guarantee);
    }
    help.back() = '.';
    cmd.add_option("--search", search, help)
        ->check(CLI::IsMember(search_names()))
        ->default_str("the fastest that serves the method");
  }
  cmd.add_option("--epsilon", epsilon, "early stop of a ray's model, in [0, 0.5)")
      ->check(number_in(0.0, 0.5, /*open_low=*/false, /*open_high=*/true))
      ->capture_default_str();
  cmd.add_option("--lambda", lambda, "latombe's travel penalty [1/m]")
      ->check(number_in(0.0, 1e3))
      ->capture_default_str();
  add_threads_option(cmd, threads, "threads (0 = all cores); results do not depend on it");
  cmd.add_option("--horizon", horizon,
                 "views planned ahead (docs/decision.md, 'Planning a sequence'): the K views that "
                 "jointly see the most unobserved cells, toured from the current pose; the tour's "
                 "first is taken, and the plan made again after the scan. 1 with no travel weight "
                 "is the one-view decision (survival and greedy)")
      ->check(whole_in(1, SequenceConfig::kMaxHorizon))
      ->capture_default_str();
  cmd.add_option("--travel-weight", travel_weight,
                 "what a metre of the sequence's tour costs, as a share of the best single "
                 "view's expected cells seen [1/m]")
      ->check(number_in(0.0, 1e3))
      ->capture_default_str();
  cmd.add_option("--sample", sample,
                 "a sequence's per-cell values on one unobserved cell in N, a power of two in "
                 "[1, 65536] (estimates, for hundreds of views; 1: exact)")
      ->check(whole_in(1, 65536))
      ->capture_default_str();
  cmd.add_option("--swept-rays", swept_rays,
                 "the swept search's rays across a view's image in its first round (the "
                 "leaders get twice as many)")
      ->check(whole_in(1, 4096))
      ->capture_default_str();
  cmd.add_option("--shortlist", shortlist,
                 "the sequence considers only this many candidates, those of highest single-view "
                 "value; their per-cell visibilities are held in memory [views]")
      ->check(whole_in(1, kMaxIndex))
      ->capture_default_str();
}

void CandidateOptions::add_to(CLI::App& cmd) {
  std::vector<std::string> names;
  std::string help =
      "the candidate views (default: the scene's own, a table top's ring, an "
      "object's view-sphere):";
  for (const CandidateSetRow& row : candidate_sets()) {
    if (row.needs_map || row.needs_list) continue;  // found in a map, or the user's list
    names.emplace_back(row.name);
    help += fmt::format(" {} ({});", row.name, row.help);
  }
  help.back() = ' ';
  cmd.add_option("--candidates", candidates, help)->check(CLI::IsMember(names));
  cmd.add_option("--views", views,
                 "ring, sphere, view-sphere: how many candidate views (0: the set's own; a ring's "
                 "is its positions times its yaw offsets)")
      ->check(whole_in(0, static_cast<int>(kMaxCandidateViews)))
      ->capture_default_str();
  cmd.add_option("--view-radius", view_radius,
                 "ring, sphere, view-sphere: the views' distance from the target (0: the set's "
                 "own) [m]")
      ->check(number_in(0.0, 1e3))
      ->capture_default_str();
  cmd.add_option("--arm-base", arm_base,
                 "hemisphere: the arm's base x,y,z [m] (default: the scene's arm, else none)");
  cmd.add_option("--reach", reach,
                 "hemisphere: the arm's reach from its base [m] (default: the scene's arm, else "
                 "unlimited)")
      ->check(number_in(0.0, 1e3, /*open_low=*/true));
  cmd.add_option("--view-spacing", spacing,
                 "hemisphere: arc between neighbouring views of a ring [m]; sets the view count")
      ->check(number_in(0.0, 10.0, /*open_low=*/true))
      ->capture_default_str();
  cmd.add_option("--hemisphere-radii", radii,
                 "hemisphere: distances of its rings of views from the scene's target, r1,r2,... "
                 "[m]")
      ->default_str(fmt::format("{}", fmt::join(HemisphereConfig{}.radii, ",")));
  cmd.add_option("--coverage-tolerance", coverage_tolerance,
                 "surface coverage counts an object surface cell once a scan point lies in it "
                 "(0, MA-SCVP's), in it or a neighbour (1) [cells], or within a distance of it "
                 "(5mm, PB-NBV's); the greedy oracle and the yardstick's denominator follow "
                 "(default: 1 on a table top, 0 for objects)");
  cmd.add_option("--object-radius", object_radius,
                 "objects: each object's bounding sphere is scaled to this radius (the view "
                 "sphere keeps its distance from it) [m]")
      ->check(number_in(0.0, 1e3, /*open_low=*/true))
      ->capture_default_str();
}

sim::ObjectProtocol CandidateOptions::object_protocol() const {
  sim::ObjectProtocol protocol;
  protocol.object_radius = object_radius;
  if (views > 0) protocol.views = views;
  if (view_radius > 0.0) {
    protocol.view_radius = view_radius;
  } else {
    // NOTE: the default sphere keeps the default distance from a larger or smaller object.
    protocol.view_radius += object_radius - sim::ObjectProtocol{}.object_radius;
  }
  protocol.resolution *= object_radius / sim::ObjectProtocol{}.object_radius;
  from_options([&] { protocol.validate(); });
  return protocol;
}

void CandidateOptions::apply(ExplorationConfig& config, sim::SceneKind kind) const {
  config.candidates = candidates;
  config.views.views = views;
  config.views.radius = view_radius;
  const bool hemisphere = candidates == "hemisphere";
  const bool arm_given = !arm_base.empty() || reach > 0.0;
  if (arm_given && !hemisphere) {
    throw UsageError("--arm-base and --reach bound an arm's views: give --candidates hemisphere");
  }
  if (arm_base.empty() != !(reach > 0.0)) {
    throw UsageError(
        "--arm-base and --reach come together: the arm's base x,y,z and its reach [m]");
  }
  config.hemisphere.spacing = spacing;
  config.coverage_tolerance =
      coverage_tolerance.empty()
          ? CoverageTolerance(kind == sim::SceneKind::kObject ? 0 : 1)
          : from_options([&] { return parse_coverage_tolerance(coverage_tolerance); });
  // NOTE: an arm places the sensor on an object's view sphere to within a millimetre, as the
  // field's simulators take it: the scene's pose noise (none) rather than a mobile base's.
  if (kind == sim::SceneKind::kObject) config.pose_noise.reset();
  if (!radii.empty()) config.hemisphere.radii = parse_numbers(radii, "--hemisphere-radii");
  if (reach > 0.0) {
    ArmReach arm;
    const std::vector<double> xyz = parse_numbers(arm_base, "--arm-base");
    if (xyz.size() != 3) {
      throw UsageError(fmt::format("--arm-base '{}' must be three numbers x,y,z [m]", arm_base));
    }
    arm.base = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
    arm.reach = reach;
    config.arm = arm;
  }
  // NOTE: the views --view-spacing and --hemisphere-radii make are counted here, before the
  // scene is built: too many is a command line to change (exit 2), not a run that fails.
  if (hemisphere) {
    from_options([&] { config.hemisphere.validate(); });
  }
}

AlphaSetting PlanningOptions::alpha_setting(double literal) const {
  return as_option([&] { return PlanningSettings::alpha_setting(literal); });
}

PlannerConfig PlanningOptions::planner_config(double literal_alpha) const {
  return as_option([&] { return PlanningSettings::planner_config(literal_alpha); });
}

void MappingOptions::add_to(CLI::App& cmd) {
  cmd.add_option("--integration", integration, "scan integration: paper or endpoint")
      ->capture_default_str();
  cmd.add_flag("!--no-icp", icp, "trust the believed poses, no scan-to-map registration");
  cmd.add_flag("!--no-segmentation", segmentation, "integrate the table's points too");
  cmd.add_flag("!--no-hole-filling", hole_filling, "skip the MRF/ICM hole filling");
}

MapperConfig MappingOptions::mapper_config(const sim::Scene& scene) const {
  MapperConfig config = default_mapper_config(scene);
  config.integration.mode = from_options([&] { return parse_integration_mode(integration); });
  config.integration.hole_filling.enabled = hole_filling;
  config.register_scans = icp;
  config.segment_table = config.segment_table && segmentation;
  return config;
}

double grid_bytes_per_cell(int threads) {
  const int n =
      threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return mapping_bytes_per_cell(n);
}

void add_memory_option(CLI::App& cmd, std::uint64_t& bytes) {
  cmd.add_option("--max-memory", bytes,
                 "refuse a run whose grid needs more than this (bytes, or 512M, 4G; 0: what the "
                 "machine has available)")
      ->transform(memory_size())
      ->capture_default_str();
}

void add_work_option(CLI::App& cmd, double& seconds) {
  cmd.add_option("--max-work", seconds,
                 fmt::format("refuse a decision estimated to take more than this, before any of it "
                             "is computed: its candidates' rays through the grid's cells in "
                             "their frusta at {} ns a ray-cell step, the worst case [s]",
                             kNanosecondsPerStep))
      ->check(number_in(0.0, 1e9, /*open_low=*/true))
      ->capture_default_str();
}

WorkBudget work_budget(double max_work, std::uint64_t max_memory) {
  WorkBudget budget;
  budget.max_seconds = max_work;
  budget.max_bytes = max_memory;
  return budget;
}

void check_decision_budget(const DecisionCost& cost, const WorkBudget& budget, std::uint64_t cells,
                           int threads) {
  check_decision(cost, budget,
                 static_cast<double>(cells) * grid_bytes_per_cell(threads) + kFixedRunBytes);
}

void add_threads_option(CLI::App& cmd, int& threads, const std::string& description) {
  cmd.add_option("--threads,-j", threads, description)
      ->check(whole_in(0, kMaxThreads))
      ->capture_default_str();
}

}  // namespace vantage::cli
