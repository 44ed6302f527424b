#pragma once
/// @file
/// A decision that looks past the next scan (issue 26; docs/decision.md, "Planning a sequence"):
/// choose K views that together see the most unobserved cells, order them into the shortest
/// open tour from the sensor's pose, take the tour's first view, and plan again after the scan.
///
/// A cell that an earlier view of the sequence is predicted to see is not counted again: with
/// v_k(c) the survival reading's visibility of cell c from view k (greedy: 1 or 0), the joint
/// value is J(S) = sum_c [1 - prod_{k in S} (1 - v_k(c))] expected cells seen (greedy: the size
/// of the union). J is monotone and submodular, so picking views one by one by their marginal
/// value is within (1 - 1/e) of the best K-set (Nemhauser et al. 1978). The tour's length is
/// the cost, traded against J by a travel weight.

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <vector>

#include "vantage/gain/evaluators/view_cells.hpp"
#include "vantage/gain/types.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/planner/sequence_config.hpp"
#include "vantage/planner/types.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// An open tour from the sensor's pose through some views.
struct OpenTour {
  std::vector<std::size_t> order;  ///< indices of the views, in the order visited
  double length = 0.0;             ///< [m]
};

/// The shortest open tour from the start through n views, by brute force over the n! orders
/// (ties: the lexicographically first order). `from_start[i]`: start to view i [m];
/// `between[i * n + j]`: view i to view j [m]. Throws std::invalid_argument when the sizes do not
/// match or n exceeds SequenceConfig::kMaxHorizon + 2.
OpenTour shortest_open_tour(std::span<const double> from_start, std::span<const double> between);

/// J(S) of the views `views` (each list ascending in cell): sum over the cells any of them holds
/// of 1 - prod (1 - v) [cells]. Greedy's lists (v = 1) give the size of their union.
double joint_cells(std::span<const ViewCells* const> views);

/// The decision and what it planned.
struct SequencePlan {
  std::size_t first = 0;            ///< the view to take now: the tour's first
  std::vector<std::size_t> tour;    ///< the chosen views in the tour's order
  std::vector<std::size_t> chosen;  ///< ... in the order the greedy selection added them
  double value = 0.0;               ///< J of the chosen views [cells]
  double tour_length = 0.0;         ///< the tour from the current pose [m]
  /// Every view's single-view value: ViewGain::cells (and greedy's gain) exactly as the exact
  /// evaluation computes it; the survival reading's gain in bits is left 0.
  std::vector<ViewGain> gains;
  /// Every view's score at the selection's first step: its value less the travel weight times
  /// the best value times its travel [cells].
  std::vector<double> scores;
  std::size_t shortlisted = 0;  ///< views whose per-cell visibilities were computed
};

/// Plans a sequence over `views` (one frustum per candidate; `travel[i]` from the current pose
/// to view i [m]) under `gain.method` (plans_sequences: survival or greedy in cells, or the surface
/// model, whose cells' credits, each the chance that the view adds the surface there, stand in for
/// the visibilities of J(S)). With horizon 1 and travel
/// weight 0 the choice is the exact evaluation's argmax (ties: the lower index), the one-view
/// decision's. Deterministic for any `gain.num_threads`. Throws std::invalid_argument for
/// another method, no views or sizes that do not match.
SequencePlan plan_sequence(const OccupancyGrid& grid, std::span<const Frustum> views,
                           std::span<const double> travel, const GainConfig& gain,
                           const SequenceConfig& config);

/// The decision by a sequence (PlannerConfig::sequence active, or PlannerMethod::kSequence): the
/// tour's first view, and for it the full prediction after the decision. Throws
/// std::invalid_argument for a candidate of several views.
Plan decide_by_sequence(const OccupancyGrid& grid, std::span<const Candidate> candidates,
                        const PlannerConfig& config);

}  // namespace vantage
