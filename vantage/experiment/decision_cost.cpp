#include "vantage/experiment/decision_cost.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

#include "vantage/gain/methods.hpp"
#include "vantage/map/traversal.hpp"
#include "vantage/planner/search.hpp"
#include "vantage/util/memory.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// Rays of the closed form across a view's image, and views sampled from a candidate list.
constexpr int kRaysAcross = 16, kRaysUp = 12;
constexpr std::size_t kSampledViews = 16;

/// The swept search's rounds (planner/searches/swept.cpp): 12 leaders cast again at twice the
/// rays a side, at most 8 finalists raced on nested samples of their exact cells up to all of
/// them, which costs about two full evaluations each (measured: 2.5 s for the race of 3 000
/// views on 80^3 unobserved cells, where one full evaluation takes 0.16 s).
constexpr double kSweptSecondViews = 12.0, kSweptSecondFactor = 4.0, kSweptFinalists = 16.0;

/// A swept ray's step through an unobserved cell (it credits its cone's volume there), and what
/// setting up one of its rays costs, in the exact walk's steps: fitted to the swept search on a
/// grid of unobserved cells, 6.5 ns a step and 310 ns a ray against the exact walk's 4.6 ns a
/// step (docs/robustness.md, "Work").
constexpr double kSweptStepWeight = 1.5, kSweptRaySteps = 70.0;

/// What a decision holds a candidate (its frustum, gains, scores, ranking, its row of the
/// results), with room to spare [bytes].
constexpr double kBytesPerCandidate = 2048.0;
/// What a metric's evaluation holds a grid cell beside the grid (MetricEvaluator): its snapshot's
/// code (1 to 4 B), and for a metric that reads distances the distance to the nearest occupied
/// cell (4 B) and, for those it may credit, the cell's index (4 B); at most [bytes].
constexpr double kMetricBytesPerCell = 4.0, kDistanceBytesPerCell = 8.0;
/// A target of a per-cell list: its cell (4 B), its visibility (8 B) and the sequence's dense
/// index of it (4 B) and of its union (4 B) [bytes].
constexpr double kBytesPerListedCell = 20.0;

}  // namespace

ViewCost view_cost(const GridSpec& spec, const Frustum& view, int swept_rays) {
  const SensorFov& fov = view.fov();
  const double tan_h = std::tan(0.5 * fov.h_fov), tan_v = std::tan(0.5 * fov.v_fov);
  const double h = spec.resolution;
  const Eigen::Matrix3d R = view.T_world_sensor().linear();
  const Eigen::Vector3d origin = view.origin();
  const Eigen::Vector3d lo = spec.origin, hi = spec.max_corner();
  // The pixel's area on the image plane at unit distance; its solid angle is that over |p|^3.
  const double pixel = (2.0 * tan_h / kRaysAcross) * (2.0 * tan_v / kRaysUp);
  ViewCost cost;
  for (int i = 0; i < kRaysAcross; ++i) {
    for (int j = 0; j < kRaysUp; ++j) {
      const Eigen::Vector3d p(1.0, tan_h * (2.0 * (i + 0.5) / kRaysAcross - 1.0),
                              tan_v * (2.0 * (j + 0.5) / kRaysUp - 1.0));
      const double omega = pixel / std::pow(p.norm(), 3);  // [sr]
      const Eigen::Vector3d dir = R * p.normalized();
      const auto [t0, t1] = clip_to_box(lo, hi, origin, dir);
      const double enter = std::max(t0, 0.0);
      const double r0 = std::max(enter, fov.min_range), r1 = std::min(t1, fov.max_range);
      if (!(r1 > r0)) continue;
      // Cells a unit of length crosses along dir (the walk's steps per metre, times h).
      const double crossings = dir.cwiseAbs().sum();
      const double volume = omega * (std::pow(r1, 3) - std::pow(r0, 3)) / 3.0;  // [m^3]
      cost.cells += volume / std::pow(h, 3);
      // Each cell at distance r is reached by its own ray, which walks (r - enter) * crossings
      // / h cells of the grid: the integral of r^2 (r - enter) over [r0, r1], plus the cell.
      const double walk = (std::pow(r1, 4) - std::pow(r0, 4)) / 4.0 -
                          enter * (std::pow(r1, 3) - std::pow(r0, 3)) / 3.0;
      cost.exact_steps += omega * crossings * walk / std::pow(h, 4) + volume / std::pow(h, 3);
      const double ray_walk = (r1 - enter) * crossings / h + 1.0;
      cost.ray_cells += ray_walk / (kRaysAcross * kRaysUp);
      // Rays 1/sqrt(2) cell apart where the range ends: 2 fov.max_range^2 / h^2 a steradian.
      cost.outward_steps += omega * 2.0 * fov.max_range * fov.max_range / (h * h) * ray_walk;
    }
  }
  const double across = std::max(tan_h, tan_v);
  cost.swept_rays =
      static_cast<double>(swept_rays) * swept_rays * (tan_h / across) * (tan_v / across);
  return cost;
}

namespace {

/// The mean cost of a view over at most kSampledViews of `views`, spread evenly.
template <typename ViewAt>
ViewCost mean_view_cost(const GridSpec& spec, std::size_t n, const ViewAt& view_at,
                        int swept_rays) {
  ViewCost mean;
  const std::size_t samples = std::min(n, kSampledViews);
  const double share = samples > 0 ? 1.0 / static_cast<double>(samples) : 0.0;
  for (std::size_t s = 0; s < samples; ++s) {
    const ViewCost c = view_cost(spec, view_at(s * n / samples), swept_rays);
    mean.cells += c.cells * share;
    mean.exact_steps += c.exact_steps * share;
    mean.outward_steps += c.outward_steps * share;
    mean.swept_rays += c.swept_rays * share;
    mean.ray_cells += c.ray_cells * share;
  }
  return mean;
}

DecisionCost cost_of(const ViewCost& v, std::size_t views, std::size_t candidates,
                     const PlannerConfig& config, double unobserved) {
  DecisionCost cost;
  cost.views = views;
  cost.cells_per_view = v.cells;
  const double n = static_cast<double>(views);
  const double u = std::clamp(unobserved, 0.0, 1.0);
  // One exact evaluation of a view: one walk a target, the unobserved cells in view.
  const double exact = u * v.exact_steps;
  // The swept search's first round on a view: its rays, each set up and stepping through the
  // unobserved cells one by one.
  const double swept = v.swept_rays * (kSweptRaySteps + kSweptStepWeight * u * v.ray_cells);
  cost.bytes = kBytesPerCandidate * static_cast<double>(candidates);
  const Decider decider = resolve_decider(config);
  if (!decider.search) {
    const SequenceConfig sequence = sequence_of(config);
    // plan_sequence: every view's single-view value (exact, or on one cell in 2^k), then the
    // shortlist's per-cell lists, its travel table and the greedy steps over them.
    const double rate = std::ldexp(1.0, sequence.sample_bits);
    const double m = std::min(n, static_cast<double>(sequence.shortlist));
    const double listed = u * v.cells / rate;  // a view's listed targets
    cost.path =
        cat("the sequence (", views, " views, a shortlist of ", static_cast<std::size_t>(m), ")");
    cost.steps = n * exact / rate;
    if (sequence.horizon > 1) {
      if (sequence.sample_bits == 0) cost.steps += m * exact;
      cost.steps += sequence.horizon * m * listed + m * m;
      cost.bytes += m * m * static_cast<double>(sizeof(double)) +
                    (sequence.sample_bits > 0 ? n : m) * listed * kBytesPerListedCell;
    }
    return cost;
  }
  const MethodTraits& traits = method_traits(config.method.gain);
  // A full evaluation: a metric's rays outward (every third of them but for exact), a target
  // model's one walk a target.
  const double full =
      traits.metric != nullptr
          ? v.outward_steps / (config.gain.evaluation == GainEvaluation::kExact ? 1.0 : 3.0)
          : exact;
  const DecisionSearch search = *decider.search;
  if (search == DecisionSearch::kSwept) {
    cost.path = cat("the swept search over ", views, " views");
    cost.steps = n * swept + std::min(n, kSweptSecondViews) * kSweptSecondFactor * swept +
                 std::min(n, kSweptFinalists) * exact;
  } else {
    // NOTE: the pruned search's worst case, every view evaluated: its bounds are the map's.
    cost.path = cat("the ", to_string(search), " search over ", views, " views");
    cost.steps = n * full;
  }
  // NOTE: a counting method's gains are greedy's, and its reference costs nothing (search.cpp).
  if (config.greedy_reference && decision_quantity(config) != GainQuantity::kCount) {
    cost.steps += n * exact;
  }
  return cost;
}

/// `cost` with what the method's evaluation holds per cell of the grid `spec`.
DecisionCost with_grid_bytes(DecisionCost cost, const GridSpec& spec, const PlannerConfig& config) {
  const MethodTraits& traits = method_traits(config.method.gain);
  if (traits.metric == nullptr || sequence_of(config).active()) return cost;
  const double per_cell =
      kMetricBytesPerCell + (traits.needs_distances ? kDistanceBytesPerCell : 0.0);
  cost.bytes += per_cell * static_cast<double>(spec.num_cells());
  return cost;
}

}  // namespace

DecisionCost estimate_decision(const GridSpec& spec, std::span<const Candidate> candidates,
                               const PlannerConfig& config, double unobserved) {
  // NOTE: an office stop's sweep is several views; its frusta are each a view of the cost.
  std::vector<const Frustum*> views;
  for (const Candidate& c : candidates) {
    views.push_back(&c.view);
    for (const Frustum& more : c.more_views) views.push_back(&more);
  }
  const ViewCost mean = mean_view_cost(
      spec, views.size(), [&](std::size_t i) -> const Frustum& { return *views[i]; },
      config.swept_rays);
  return with_grid_bytes(cost_of(mean, views.size(), candidates.size(), config, unobserved), spec,
                         config);
}

DecisionCost estimate_decision(const GridSpec& spec, std::span<const Eigen::Isometry3d> poses,
                               const SensorFov& fov, const PlannerConfig& config,
                               double unobserved) {
  const ViewCost mean = mean_view_cost(
      spec, poses.size(), [&](std::size_t i) { return Frustum(poses[i], fov); }, config.swept_rays);
  return with_grid_bytes(cost_of(mean, poses.size(), poses.size(), config, unobserved), spec,
                         config);
}

double unobserved_share(const OccupancyGrid& grid) {
  const std::size_t cells = grid.spec().num_cells();
  return cells == 0 ? 0.0
                    : static_cast<double>(grid.counts().unobserved) / static_cast<double>(cells);
}

double mapping_grid_bytes(const GridSpec& spec, int threads) {
  const int n =
      threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return static_cast<double>(spec.num_cells()) * mapping_bytes_per_cell(n);
}

std::optional<DecisionCost> estimate_run_decision(const sim::Scene& scene,
                                                  const ExplorationConfig& config) {
  if (scene.kind == sim::SceneKind::kOffice) return std::nullopt;
  PlannerConfig planner = config.planner;
  planner.greedy_reference = false;  // explore predicts greedy's count for the chosen view only
  const std::vector<Eigen::Isometry3d> poses = run_candidates(scene, config);
  return estimate_decision(scene.grid, poses, scene.fov(), planner, /*unobserved=*/0.0);
}

void check_decision(const DecisionCost& cost, const WorkBudget& budget, double grid_bytes) {
  const auto what = [&] {
    return cat(cost.path, ", about ", static_cast<long long>(cost.cells_per_view + 0.5),
               " grid cells in each view's frustum");
  };
  // NOTE: memory first: a decision past it fails where one past its time only runs long.
  const bool given = budget.max_bytes > 0;
  const double limit = static_cast<double>(given ? budget.max_bytes : available_memory());
  if (limit > 0.0 && cost.bytes + grid_bytes > limit) {
    throw WorkBudgetError(
        cat(what(), ", needs about ", describe_bytes(cost.bytes), " beside the grid's ",
            describe_bytes(grid_bytes), ", more than ",
            given ? cat(budget.memory_option, " ", describe_bytes(limit))
                  : cat("the ", describe_bytes(limit), " this machine has available (",
                        budget.memory_option, ")"),
            ": decide among fewer views (or a smaller shortlist, or a sample)"),
        /*past_memory=*/true);
  }
  if (cost.seconds() > budget.max_seconds) {
    throw WorkBudgetError(
        cat(what(), ", is estimated at ", describe_seconds(cost.seconds()), " of work (",
            significant(cost.steps), " ray-cell steps at ", kNanosecondsPerStep, " ns), more than ",
            budget.work_option, " ", budget.max_seconds,
            " s allows: raise it, or decide among fewer views (or a smaller "
            "shortlist)"),
        /*past_memory=*/false);
  }
}

void check_decision_on(const OccupancyGrid& grid, std::span<const Candidate> candidates,
                       const PlannerConfig& config, const WorkBudget& budget) {
  check_decision(estimate_decision(grid.spec(), candidates, config, unobserved_share(grid)), budget,
                 mapping_grid_bytes(grid.spec(), config.gain.num_threads));
}

double simulated_rays_per_scan(const sim::SensorConfig& sensor) {
  if (sensor.type == sim::SensorType::kRgbd) {
    return static_cast<double>(sensor.width) * static_cast<double>(sensor.height);
  }
  return std::ceil(sensor.fov.h_fov / sensor.angular_resolution) *
         std::ceil(sensor.fov.v_fov / sensor.tilt_resolution);
}

double surface_truth_rays(const sim::Scene& scene, std::size_t candidates) {
  const double scans = static_cast<double>(candidates + scene.start_poses.size());
  return scans * simulated_rays_per_scan(scene.sensor);
}

void check_surface_truth(const sim::Scene& scene, std::size_t candidates,
                         const WorkBudget& budget) {
  const double rays = surface_truth_rays(scene, candidates);
  const double seconds = rays * kNanosecondsPerSimulatedRay * 1e-9;
  if (seconds <= budget.max_seconds) return;
  throw WorkBudgetError(
      cat("the surface yardstick's noise-free scans of ", candidates, " candidate views and ",
          scene.start_poses.size(), " starts (", significant(rays), " simulated rays at ",
          kNanosecondsPerSimulatedRay, " ns) are estimated at ", describe_seconds(seconds),
          " of work, more than ", budget.work_option, " ", describe_seconds(budget.max_seconds),
          " allows: raise it, or explore among fewer views (a wider --view-spacing)"),
      /*past_memory=*/false);
}

}  // namespace vantage
