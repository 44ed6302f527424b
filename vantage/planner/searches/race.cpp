#include "vantage/planner/searches/race.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/evaluators/view_cells.hpp"
#include "vantage/planner/choose.hpp"

namespace vantage::detail {
namespace {

/// A candidate's targets: linear index and the sum of its views' v_M, ascending by index.
using Targets = std::vector<std::pair<std::uint32_t, double>>;

Targets merged(std::span<const ViewCells> lists) {
  Targets out;
  for (const ViewCells& list : lists) {
    for (std::size_t i = 0; i < list.cells.size(); ++i)
      out.emplace_back(list.cells[i], list.seen[i]);
  }
  if (lists.size() == 1) return out;  // one view: its list is already ascending, one entry a cell
  std::stable_sort(out.begin(), out.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  Targets sums;
  for (const auto& [cell, seen] : out) {
    if (!sums.empty() && sums.back().first == cell) {
      sums.back().second += seen;
    } else {
      sums.emplace_back(cell, seen);
    }
  }
  return sums;
}

/// Per boost value o (the cells sampled 2^o times as often, race_candidates), a sum.
using ByBoost = std::array<double, kMostBoost + 1>;

/// The boost of `cell`: 0 without boosts.
std::uint8_t boost_of(std::span<const std::uint8_t> boost, std::uint32_t cell) {
  return boost.empty() ? std::uint8_t{0} : boost[cell];
}

/// Per boost value, the sum and the sum of squares over the union of two candidates' targets of
/// fa * a_i - fb * b_i (a target one lacks counts 0 there).
struct Difference {
  ByBoost sum{}, sq{};
};
Difference difference(const Targets& a, double fa, const Targets& b, double fb,
                      std::span<const std::uint8_t> boost) {
  Difference out;
  ByBoost& sum = out.sum;
  ByBoost& sq = out.sq;
  std::size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    double d = 0.0;
    std::uint32_t cell;
    if (j == b.size() || (i < a.size() && a[i].first < b[j].first)) {
      cell = a[i].first;
      d = fa * a[i++].second;
    } else if (i == a.size() || b[j].first < a[i].first) {
      cell = b[j].first;
      d = -fb * b[j++].second;
    } else {
      cell = a[i].first;
      d = fa * a[i++].second - fb * b[j++].second;
    }
    const std::uint8_t o = boost_of(boost, cell);
    sum[o] += d;
    sq[o] += d * d;
  }
  return out;
}

/// The Horvitz-Thompson weight at the sample of `bits` of a cell of boost `o`: one over the
/// chance that the sample holds it.
double weight(int bits, int o) { return std::ldexp(1.0, std::max(0, bits - o)); }

/// Two lists of targets in one, ascending by index (they hold no index in common).
Targets united(const Targets& a, const Targets& b) {
  Targets out(a.size() + b.size());
  std::merge(a.begin(), a.end(), b.begin(), b.end(), out.begin(),
             [](const auto& x, const auto& y) { return x.first < y.first; });
  return out;
}

/// The unseen target (RaceRules::unseen) at the sample of `bits`: the largest value of a boost
/// at its weight, times the largest factor of the candidates `alive`.
double unseen_target(const ByBoost& largest, const std::vector<std::size_t>& alive,
                     std::span<const double> factor, int bits) {
  double most_factor = 0.0, unseen = 0.0;
  for (const std::size_t k : alive) most_factor = std::max(most_factor, factor[k]);
  for (int o = 0; o <= kMostBoost; ++o) {
    unseen = std::max(unseen, weight(bits, o) * most_factor * largest[o]);
  }
  return unseen;
}

/// The candidates of `alive` that stay in the race after the sample of `bits`: the leader
/// (`alive[lead]`) and every one whose gap to it is not beyond `rules.standard_errors` of the
/// gap's error, less the tolerance. A pair's difference on one sample is estimated with its own
/// error, far smaller than the sum of the two estimates' errors when the views see many of the
/// same cells.
std::vector<std::size_t> still_racing(const std::vector<std::size_t>& alive, std::size_t lead,
                                      const std::vector<Targets>& targets,
                                      std::span<const double> factor,
                                      const std::vector<double>& scores, double unseen, int bits,
                                      const RaceRules& rules) {
  // NOTE: each pair's difference side by side (within the caller's arena), kept in order.
  std::vector<std::uint8_t> stays(alive.size(), 1);
  tbb::parallel_for(std::size_t{0}, alive.size(), [&](std::size_t a) {
    if (a == lead) return;
    const auto [sum, sq] = difference(targets[alive[lead]], factor[alive[lead]], targets[alive[a]],
                                      factor[alive[a]], rules.boost);
    double gap = 0.0, variance = 0.0;
    for (int o = 0; o <= kMostBoost; ++o) {
      const double w = weight(bits, o);
      gap += w * sum[o];
      variance += w * (w - 1.0) * sq[o];
    }
    const double error = std::sqrt(variance + unseen * unseen);
    const double slack = rules.tolerance * scores[lead];
    if (gap + slack > rules.standard_errors * error && gap + slack > 0.0) stays[a] = 0;
  });
  std::vector<std::size_t> next;
  for (std::size_t a = 0; a < alive.size(); ++a) {
    if (stays[a]) next.push_back(alive[a]);
  }
  return next;
}

/// The targets a view's list is expected to hold among `next` new cells, from `lists`, the views'
/// lists among the `last` cells of the last sample.
double new_targets(const std::vector<ViewCells>& lists, std::size_t last, std::size_t next) {
  double targets = 0.0;
  for (const ViewCells& l : lists) targets += static_cast<double>(l.targets);
  return targets * static_cast<double>(next) /
         (static_cast<double>(std::max<std::size_t>(lists.size(), 1)) *
          static_cast<double>(std::max<std::size_t>(last, 1)));
}

}  // namespace

Race race_candidates(const std::vector<std::vector<std::uint32_t>>& levels,
                     std::span<const Frustum> frusta, std::span<const std::size_t> first,
                     std::span<const double> factor, const TargetLister& list,
                     const RaceRules& rules) {
  const std::span<const std::uint8_t> boost = rules.boost;
  const std::size_t n = first.size() - 1;
  std::vector<std::size_t> alive(n);
  for (std::size_t k = 0; k < n; ++k) alive[k] = k;
  Race race;
  race.scores.assign(n, 0.0);
  std::vector<Targets> targets(n);  // per finalist, on the sample so far
  ByBoost largest{};                // per boost, the largest value listed so far
  // NOTE: each sample doubles the last and holds it: only the new cells are cast.
  for (int bits = static_cast<int>(levels.size()) - 1;; --bits) {
    std::vector<Frustum> views;
    std::vector<std::size_t> which, starts;
    for (const std::size_t k : alive) {
      starts.push_back(views.size());
      for (std::size_t v = first[k]; v < first[k + 1]; ++v) {
        views.push_back(frusta[v]);
        which.push_back(v);
      }
    }
    starts.push_back(views.size());
    const std::vector<ViewCells> lists = list(views, which, levels[static_cast<std::size_t>(bits)]);
    for (const ViewCells& l : lists) {
      for (std::size_t k = 0; k < l.cells.size(); ++k) {
        double& m = largest[boost_of(boost, l.cells[k])];
        m = std::max(m, std::abs(l.seen[k]));
      }
    }
    const double unseen = rules.unseen ? unseen_target(largest, alive, factor, bits) : 0.0;
    // NOTE: each candidate's own lists and score, side by side (within the caller's arena).
    std::vector<double> scores(alive.size());
    tbb::parallel_for(std::size_t{0}, alive.size(), [&](std::size_t a) {
      Targets& mine = targets[alive[a]];
      mine = united(mine, merged(std::span(lists).subspan(starts[a], starts[a + 1] - starts[a])));
      ByBoost sum{};
      for (const auto& [cell, seen] : mine) sum[boost_of(boost, cell)] += seen;
      // NOTE: a power of two times the sum: without boosts, 2^bits times it to the last bit.
      double score = 0.0;
      for (int o = 0; o <= kMostBoost; ++o) score += weight(bits, o) * factor[alive[a]] * sum[o];
      scores[a] = score;
      race.scores[alive[a]] = score;
    });
    race.bits = bits;
    const std::size_t lead = choose_best(scores);
    if (bits == 0) {
      race.winner = alive[lead];
      race.exact = true;
      return race;
    }
    const std::size_t leader = alive[lead];  // never drops out
    alive = still_racing(alive, lead, targets, factor, scores, unseen, bits, rules);
    if (alive.size() == 1) {
      race.winner = alive.front();
      return race;
    }
    if (rules.most_new_targets > 0.0 &&
        new_targets(lists, levels[static_cast<std::size_t>(bits)].size(),
                    levels[static_cast<std::size_t>(bits - 1)].size()) > rules.most_new_targets) {
      race.winner = leader;
      race.alive = std::move(alive);
      return race;
    }
  }
}

Race race_candidates(const ClassMap& map, std::span<const Frustum> frusta,
                     std::span<const std::size_t> first, std::span<const double> factor,
                     const GainConfig& config, std::size_t max_sample, double tolerance) {
  return race_candidates(
      unobserved_by_sample(map, max_sample), frusta, first, factor,
      [&](std::span<const Frustum> views, std::span<const std::size_t>,
          std::span<const std::uint32_t> cells) {
        return exact_view_cells(map, views, config, cells);
      },
      RaceRules{.tolerance = tolerance});
}

}  // namespace vantage::detail
