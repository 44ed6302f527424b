#pragma once
/// @file
/// The pruned decision (PlannerConfig::search = kPruned; docs/decision.md, "The pruned search"):
/// the exhaustive exact search's argmax, proven, without every candidate's evaluation. Every
/// candidate gets an upper bound on its score from the map's block summary (hierarchy.hpp);
/// candidates are evaluated exactly in the order of their bounds, and the search stops when no
/// bound left can beat the best exact score. Deterministic: the bounds, the order and the exact
/// evaluations do not depend on threads.

#include <cstddef>
#include <span>
#include <vector>

#include "vantage/gain/view_gain.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage::detail {

/// What a pruned search scores by.
enum class PrunedScore {
  kSurvivalCells,  ///< the survival reading's expected cells seen [cells]
  kGreedy,         ///< greedy's count [cells], times the candidate's factor (Latombe)
  kBits,           ///< eq. (4)'s gain under config.method (probabilistic or survival) [bits]
  kModelCells,     ///< the paper's model's expected cells seen, sum of v_M [cells]
};

/// What the pruned search found.
struct Pruning {
  /// Per candidate: its exact prediction where `estimated` is false, else its upper bound in
  /// the score's field (cells, or gain for kBits; ViewGain::targets 0).
  std::vector<ViewGain> gains;
  std::vector<bool> estimated;   ///< per candidate: not evaluated, `gains` holds its bound
  std::vector<double> scores;    ///< per candidate: the score, exact or its bound
  std::size_t best = 0;          ///< the candidate with the highest exact score (ties: lower index)
  std::size_t evaluated = 0;     ///< candidates evaluated exactly
  double summary_seconds = 0.0;  ///< building the snapshot and the block summary [s]
  double bound_seconds = 0.0;    ///< the bounds [s]
};

/// Chooses among the candidates whose views are `frusta[first[c] .. first[c + 1])`; candidate c's
/// score is the sum over its views of the view's value times `factor[c]` (empty: 1), in view
/// order, exactly as the exhaustive search sums it.
Pruning prune_candidates(const OccupancyGrid& grid, std::span<const Frustum> frusta,
                         std::span<const std::size_t> first, std::span<const double> factor,
                         const GainConfig& config, PrunedScore score);

}  // namespace vantage::detail
