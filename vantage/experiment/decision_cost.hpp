#pragma once
/// @file
/// A decision's cost, estimated before it runs (issue 39; docs/robustness.md, "Work"): its
/// candidates' views against the grid's cells in their frusta, by the search or sequence that
/// will decide, in ray-cell steps and bytes, and the budget's check of it. Cheap (a closed form on
/// a fixed sample of 16 views x 192 rays, whatever the candidates), deterministic, and an upper
/// bound in the worst case it assumes: every cell in view unobserved, a pruned search that prunes
/// nothing.

#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "vantage/experiment/exploration.hpp"
#include "vantage/map/grid_spec.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/planner/types.hpp"
#include "vantage/util/work.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// One view's cost against a grid whose every cell is unobserved, from its frustum clipped to
/// the grid's box.
struct ViewCost {
  double cells = 0.0;          ///< grid cells inside the frustum [cells]
  double exact_steps = 0.0;    ///< one ray from the origin to each of them [steps]
  double outward_steps = 0.0;  ///< rays 1/sqrt(2) cell apart at the far range (metrics) [steps]
  double swept_rays = 0.0;     ///< the swept search's first round of rays [rays]
  double ray_cells = 0.0;      ///< cells a ray from the origin walks, on average [cells]
};

/// The cost of `view` on the grid `spec`, with the swept search casting `swept_rays` across its
/// image: a closed form along 16 x 12 rays over the image, each standing for its pixel's cone
/// (volume and walk length where it lies inside the grid's box and the sensor's range).
ViewCost view_cost(const GridSpec& spec, const Frustum& view, int swept_rays);

/// What a decision will cost.
struct DecisionCost {
  std::size_t views = 0;        ///< frusta of every candidate (an office stop's sweep counts each)
  double cells_per_view = 0.0;  ///< the mean grid cells in a view's frustum [cells]
  double steps = 0.0;           ///< [ray-cell steps]
  double bytes = 0.0;           ///< what the decision holds beside the grid [bytes]
  std::string path;             ///< what decides: "the swept search", "the sequence", ...
  /// What to change to make it cheaper, as the option names it (the budget's names filled in).
  std::string advice;

  double seconds() const { return work_seconds(steps); }  ///< [s]
};

/// The cost of deciding among `candidates` on the grid `spec` under `config` (its search
/// resolved as plan_next_view resolves it, its sequence as sequence_of says), where
/// `unobserved` of the grid's cells are unobserved: the exact walks' targets, and the cells a
/// swept ray steps through one by one, scale with it (a free cube is crossed in one step). 1 is
/// a map not yet begun; 0 a lower bound for any map, what a check before the mapping may
/// refuse. The mean view cost is taken over at most 16 candidates spread evenly over the list.
DecisionCost estimate_decision(const GridSpec& spec, std::span<const Candidate> candidates,
                               const PlannerConfig& config, double unobserved = 1.0);

/// The same for views given as poses with one field of view.
DecisionCost estimate_decision(const GridSpec& spec, std::span<const Eigen::Isometry3d> poses,
                               const SensorFov& fov, const PlannerConfig& config,
                               double unobserved = 1.0);

/// The share of the grid's cells that are unobserved, in [0, 1], from its census.
double unobserved_share(const OccupancyGrid& grid);

/// The least one decision of a table-top run of `config` on `scene` can cost, whatever its map
/// (`unobserved` 0): its ring or hemisphere, every view open. Nothing for an office, whose
/// candidates are frontier stops found as it runs. Each decision of the run is checked again
/// on its map (ExplorationConfig::budget).
std::optional<DecisionCost> estimate_run_decision(const sim::Scene& scene,
                                                  const ExplorationConfig& config);

/// Rays one simulated scan of `sensor` casts: a depth camera's pixels, a line scanner's beams.
double simulated_rays_per_scan(const sim::SensorConfig& sensor);

/// Simulated rays of a table-top run's surface yardstick: one noise-free scan of each of
/// `candidates` views and of the scene's starts (compute_surface_truth), each
/// kNanosecondsPerSimulatedRay of work.
double surface_truth_rays(const sim::Scene& scene, std::size_t candidates);

/// Throws WorkBudgetError, one line naming the estimate and --max-work, when a table-top run's
/// surface yardstick (one noise-free scan of each of `candidates` views and of the scene's starts,
/// compute_surface_truth) is estimated past `budget`'s time: the set-up before a run's first
/// decision, which that decision's check comes too late for.
void check_surface_truth(const sim::Scene& scene, std::size_t candidates, const WorkBudget& budget);

/// The grid's bytes as a run that maps into it and plans holds them (mapping_bytes_per_cell).
double mapping_grid_bytes(const GridSpec& spec, int threads);

/// Throws WorkBudgetError, one line naming the estimate, the budget's option and what to change,
/// when `cost` exceeds `budget`'s time or (with the grid's `grid_bytes`) its memory, or the memory
/// available now when budget.max_bytes is 0.
void check_decision(const DecisionCost& cost, const WorkBudget& budget, double grid_bytes = 0.0);

/// Checks the decision among `candidates` on `grid` as it is (its unobserved share) against
/// `budget`, beside the grid's bytes at config.gain.num_threads: what plan_next_view's callers
/// ask before they call it (explore, vantage plan, Python).
void check_decision_on(const OccupancyGrid& grid, std::span<const Candidate> candidates,
                       const PlannerConfig& config, const WorkBudget& budget);

}  // namespace vantage
