#include "vantage/planner/prune.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include "vantage/gain/exact.hpp"
#include "vantage/gain/hierarchy.hpp"
#include "vantage/gain/methods.hpp"

namespace vantage::detail {
Pruning prune_candidates(const OccupancyGrid& grid, std::span<const Frustum> frusta,
                         std::span<const std::size_t> first, std::span<const double> factor,
                         const GainConfig& config, PrunedScore score) {
  config.validate();
  const std::size_t n = first.size() - 1;
  const auto factor_of = [&](std::size_t c) { return factor.empty() ? 1.0 : factor[c]; };
  Pruning out;
  const GainMap map(grid, config.num_threads);
  const ClassBlocks blocks = summarize_classes(map, frusta, config.num_threads);
  const BoundKind kind = score == PrunedScore::kSurvivalCells ? BoundKind::kSurvivalCells
                         : score == PrunedScore::kGreedy      ? BoundKind::kCount
                         : score == PrunedScore::kModelCells  ? BoundKind::kAllCells
                         : method_traits(config.method).ray == TargetRay::kSurvival
                             ? BoundKind::kSurvivalBits
                             : BoundKind::kEntropy;
  const std::vector<double> view_bounds =
      view_upper_bounds(blocks, map.spec(), map, frusta, kind, config.alpha);
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
    (score == PrunedScore::kBits ? out.gains[c].gain : out.gains[c].cells) = raw;
    if (score == PrunedScore::kGreedy) out.gains[c].gain = raw;
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
  std::vector<Frustum> first_views;
  for (std::size_t c = 0; c < n; ++c) first_views.push_back(frusta[first[c]]);
  const std::vector<std::vector<std::size_t>> by_origin = views_by_origin(first_views);
  std::vector<std::size_t> group_of(n);
  for (std::size_t g = 0; g < by_origin.size(); ++g) {
    for (const std::size_t c : by_origin[g]) group_of[c] = g;
  }
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
    std::vector<ViewGain> gains;
    switch (score) {
      case PrunedScore::kSurvivalCells:
        gains = count_view_gains(map, &blocks, views, CountRule::kSurvivalCells, config);
        break;
      case PrunedScore::kGreedy:
        gains = count_view_gains(map, &blocks, views, CountRule::kGreedy, config);
        break;
      case PrunedScore::kBits:
      case PrunedScore::kModelCells:
        gains = exact_view_gains(map, views, config);
        break;
    }
    std::size_t v = 0;
    for (const std::size_t b : batch) {
      ViewGain sum;
      double value = 0.0;
      for (std::size_t k = first[b]; k < first[b + 1]; ++k, ++v) {
        const ViewGain& g = gains[v];
        sum.gain += g.gain;
        sum.cells += g.cells;
        sum.targets += g.targets;
        value += (score == PrunedScore::kBits ? g.gain : g.cells) * factor_of(b);
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

}  // namespace vantage::detail
