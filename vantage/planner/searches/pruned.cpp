// The pruned search (DecisionSearch::kPruned; docs/decision.md, "The pruned search"): the
// exhaustive exact search's argmax, proven, without every candidate's evaluation. Every candidate
// gets an upper bound on its score from the map's block summary (hierarchy.hpp); candidates are
// evaluated exactly in the order of their bounds, and the search stops when no bound left can beat
// the best exact score. Deterministic: the bounds, the order and the exact evaluations do not
// depend on threads. It serves the target models (the paper's, the survival reading, greedy's
// count) and Latombe's weighting of greedy's.

#include <algorithm>
#include <limits>
#include <numeric>

#include "vantage/gain/evaluators/bounds.hpp"
#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/evaluators/hierarchy.hpp"
#include "vantage/planner/search.hpp"

namespace vantage {
namespace {

/// What the pruned search found.
struct Pruning {
  /// Per candidate: its exact prediction where `estimated` is false, else its upper bound in
  /// the score's field (cells, or gain for kBits; ViewGain::targets 0).
  std::vector<ViewGain> gains;
  std::vector<bool> estimated;  ///< per candidate: not evaluated, `gains` holds its bound
  std::vector<double> scores;   ///< per candidate: the score, exact or its bound
  std::size_t best = 0;         ///< the candidate with the highest exact score (ties: lower index)
  std::size_t evaluated = 0;    ///< candidates evaluated exactly
};

/// The views' exact values: counted across the map's blocks for a quantity of the cells'
/// classes alone (hierarchy.hpp), else evaluated exactly (exact.hpp).
std::vector<ViewGain> exact_values(const GainMap& map, const ClassBlocks& blocks,
                                   std::span<const Frustum> views, GainQuantity quantity,
                                   const GainConfig& config) {
  return counts_classes(quantity) ? count_view_gains(map, &blocks, views, quantity, config)
                                  : exact_view_gains(map, views, config);
}

/// The candidates grouped by the origin of their first view (views_by_origin).
struct OriginGroups {
  std::vector<std::vector<std::size_t>> candidates;  ///< per origin, its candidates
  std::vector<std::size_t> group_of;                 ///< per candidate, its origin's group
  OriginGroups(std::span<const Frustum> frusta, std::span<const std::size_t> first) {
    const std::size_t n = first.size() - 1;
    std::vector<Frustum> first_views;
    for (std::size_t c = 0; c < n; ++c) first_views.push_back(frusta[first[c]]);
    candidates = views_by_origin(first_views);
    group_of.resize(n);
    for (std::size_t g = 0; g < candidates.size(); ++g) {
      for (const std::size_t c : candidates[g]) group_of[c] = g;
    }
  }
};

/// Chooses among the candidates whose views are `frusta[first[c] .. first[c + 1])`; candidate c's
/// score is the sum over its views of the view's `quantity` times `factor[c]`, in view order,
/// exactly as the exhaustive search sums it.
Pruning prune_candidates(const OccupancyGrid& grid, std::span<const Frustum> frusta,
                         std::span<const std::size_t> first, std::span<const double> factor,
                         const GainConfig& config, GainQuantity quantity) {
  config.validate();
  const std::size_t n = first.size() - 1;
  const auto factor_of = [&](std::size_t c) { return factor.empty() ? 1.0 : factor[c]; };
  Pruning out;
  const GainMap map(grid, config.num_threads);
  const ClassBlocks blocks = summarize_classes(map, frusta, config.num_threads);
  const std::vector<double> view_bounds =
      view_upper_bounds(blocks, map.spec(), map, frusta, quantity, config.alpha);
  out.gains.assign(n, ViewGain{});
  out.estimated.assign(n, true);
  out.scores.assign(n, 0.0);
  for (std::size_t c = 0; c < n; ++c) {
    double bound = 0.0, raw = 0.0;
    for (std::size_t v = first[c]; v < first[c + 1]; ++v) {
      raw += view_bounds[v];
      bound += view_bounds[v] * factor_of(c);
    }
    out.scores[c] = bound;
    out.gains[c] = ViewGain::of(quantity, raw);
  }

  // Best first: the highest bound, ties to the lower index, as choose_best breaks them.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return out.scores[a] > out.scores[b]; });
  double best = -std::numeric_limits<double>::infinity();
  bool found = false;
  // Single-view candidates by origin: views from one origin share each target's ray
  // (exact_view_gains), so the candidates of an origin still in the race are evaluated together.
  const auto single = [&](std::size_t c) { return first[c + 1] - first[c] == 1; };
  const OriginGroups origins(frusta, first);
  const std::vector<std::vector<std::size_t>>& by_origin = origins.candidates;
  const std::vector<std::size_t>& group_of = origins.group_of;
  for (const std::size_t c : order) {
    if (!out.estimated[c]) continue;  // evaluated with another of its origin
    // NOTE: bounds are in descending order, so once one cannot beat the best, none after can.
    if (found && out.scores[c] < best) break;
    if (found && out.scores[c] == best && c > out.best) continue;
    std::vector<std::size_t> batch{c};
    if (single(c)) {
      for (const std::size_t o : by_origin[group_of[c]]) {
        if (o != c && out.estimated[o] && single(o) && (!found || out.scores[o] >= best)) {
          batch.push_back(o);
        }
      }
    }
    std::vector<Frustum> views;
    for (const std::size_t b : batch) {
      views.insert(views.end(), frusta.begin() + static_cast<std::ptrdiff_t>(first[b]),
                   frusta.begin() + static_cast<std::ptrdiff_t>(first[b + 1]));
    }
    const std::vector<ViewGain> gains = exact_values(map, blocks, views, quantity, config);
    std::size_t v = 0;
    for (const std::size_t b : batch) {
      ViewGain sum;
      double value = 0.0;
      for (std::size_t k = first[b]; k < first[b + 1]; ++k, ++v) {
        const ViewGain& g = gains[v];
        sum += g;
        value += g.value(quantity) * factor_of(b);
      }
      out.gains[b] = sum;
      out.estimated[b] = false;
      out.scores[b] = value;
      ++out.evaluated;
      if (!found || value > best || (value == best && b < out.best)) {
        best = value;
        out.best = b;
        found = true;
      }
    }
  }
  return out;
}

// NOTE: the blocks bound every quantity but a metric's value (view_upper_bounds).
bool serves(const PlannerConfig& config) {
  return ranks_by_gain(config.method) && decision_quantity(config) != GainQuantity::kMetric;
}

Plan run(const SearchInput& in) {
  const GainQuantity quantity = in.quantity();
  Pruning pruning = prune_candidates(in.grid, in.views.frusta, in.views.first, in.travel_factors(),
                                     in.gain, quantity);
  Plan plan;
  plan.search = DecisionSearch::kPruned;
  plan.best = pruning.best;
  plan.gains = std::move(pruning.gains);
  plan.estimated = std::move(pruning.estimated);
  plan.scores = std::move(pruning.scores);
  plan.evaluated = pruning.evaluated;
  // NOTE: count_view_gains computes no bits for the survival reading's cells.
  plan.bits_of_chosen_only = quantity == GainQuantity::kSurvivalCells;
  plan.seconds = in.seconds();
  report_choice(in, plan);
  return plan;
}

}  // namespace

extern const SearchTraits kPrunedSearch;
const SearchTraits kPrunedSearch = {
    DecisionSearch::kPruned,
    "exact evaluations in the order of upper bounds from the map's blocks: the exhaustive exact "
    "choice, proven; the target models (probabilistic, survival, greedy) and latombe",
    &serves, &run};

}  // namespace vantage
