#include "vantage/planner/sequence.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <utility>

#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/evaluators/hierarchy.hpp"
#include "vantage/gain/evaluators/metric_evaluator.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/gain/models/metrics/shared.hpp"
#include "vantage/gain/snapshot.hpp"
#include "vantage/util/clock.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// The shortlist: the `m` views of highest value (ties: the lower index), in ascending index.
std::vector<std::size_t> best_views(const std::vector<ViewGain>& gains, GainQuantity quantity,
                                    std::size_t m) {
  std::vector<std::size_t> order(gains.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return gains[a].value(quantity) > gains[b].value(quantity);
  });
  order.resize(std::min(m, order.size()));
  std::sort(order.begin(), order.end());
  return order;
}

/// The shortlisted views' cells renumbered into one dense range, so the joint value's state is a
/// flat array over the cells any of them may see.
struct CompactCells {
  std::size_t size = 0;                        ///< distinct cells
  std::vector<std::vector<std::uint32_t>> at;  ///< per view, each cell's dense index

  explicit CompactCells(const std::vector<ViewCells>& lists) {
    std::vector<std::uint32_t> all;
    for (const ViewCells& l : lists) all.insert(all.end(), l.cells.begin(), l.cells.end());
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    size = all.size();
    for (const ViewCells& l : lists) {
      std::vector<std::uint32_t>& dense = at.emplace_back();
      dense.reserve(l.cells.size());
      auto from = all.begin();
      for (const std::uint32_t c : l.cells) {  // ascending: one sweep through `all`
        from = std::lower_bound(from, all.end(), c);
        dense.push_back(static_cast<std::uint32_t>(from - all.begin()));
      }
    }
  }
};

}  // namespace

namespace {

/// What the sequence's values are read from: the cells' classes (the survival reading's cells,
/// greedy's count), or a metric listed cell by cell (the surface model: each cell's credit, the
/// surface it is expected to add).
struct Values {
  GainQuantity quantity;
  const ClassMap* classes = nullptr;  ///< for a quantity of the classes
  /// For a metric; the surface model's evaluator also gives every cell's distance to the
  /// nearest occupied cell, whose class gives the chance r(x) that it holds a surface
  /// (surface_class, GainConfig's rates).
  const MetricEvaluator* metric = nullptr;
};

/// The views the selection considers (shortlist positions 0 .. m-1) and what it reads of them.
struct Shortlist {
  GainQuantity quantity = GainQuantity::kCount;  ///< what a view's value is (ViewGain::value)
  std::vector<std::size_t> views;                ///< candidate views, ascending
  std::vector<double> between;   ///< [i * m + j]: the travel between views i and j [m]
  std::vector<ViewCells> lists;  ///< per view its per-cell visibilities; empty at horizon 1
  /// The surface model's: per list entry the chance r(x) that the cell holds a surface, which
  /// its credit v(x) r(x) shares with every view's (empty for the others, whose lists hold v).
  /// J(S) = sum_x r(x) [1 - prod_{k in S} (1 - v_k(x))].
  std::vector<std::vector<double>> chance;
};

/// Every view's single-view value into `gains`: bit for bit the exact evaluation's
/// (hierarchy.hpp), or its estimate from the sample's per-cell lists, which it returns so that
/// the joint values share them (empty when not sampled).
std::vector<ViewCells> single_values(const OccupancyGrid& grid, const Values& values,
                                     std::span<const Frustum> views, const GainConfig& gain,
                                     const SequenceConfig& config, std::vector<ViewGain>& gains) {
  const GainQuantity quantity = values.quantity;
  const ClassMap& classes = *values.classes;
  std::vector<ViewCells> sampled;
  if (values.metric != nullptr) {
    gains = values.metric->gains(views);
  } else if (config.sample_bits > 0) {
    const double rate = std::ldexp(1.0, config.sample_bits);
    sampled = exact_view_cells(classes, views, gain, config.sample_bits);
    for (const ViewCells& list : sampled) {
      const double cells = rate * list.sum();
      // NOTE: greedy's gain is its count; the survival reading's bits are left 0, as exactly.
      gains.push_back({quantity == GainQuantity::kCount ? cells : 0.0, cells,
                       static_cast<std::size_t>(rate) * list.targets});
    }
  } else {
    const GainMap map(grid, gain.num_threads);
    const ClassBlocks blocks = summarize_classes(map, views, gain.num_threads);
    gains = count_view_gains(map, &blocks, views, quantity, gain);
  }
  return sampled;
}

/// The shortlist of the views of highest value, with the travel between them and their
/// per-cell visibilities where a later step needs them (a horizon past 1).
Shortlist shortlist_of(std::span<const Frustum> views, const Values& values, const GainConfig& gain,
                       const SequenceConfig& config, const std::vector<ViewGain>& gains,
                       std::vector<ViewCells> sampled) {
  Shortlist s;
  s.quantity = values.quantity;
  s.views = best_views(gains, values.quantity, static_cast<std::size_t>(config.shortlist));
  const std::size_t m = s.views.size();
  s.between.assign(m * m, 0.0);
  if (config.horizon == 1) return s;
  for (std::size_t i = 0; i < m; ++i) {
    for (std::size_t j = 0; j < m; ++j) {
      if (i != j)
        s.between[i * m + j] =
            config.travel(views[s.views[i]].origin(), views[s.views[j]].origin());
    }
  }
  if (config.sample_bits > 0) {
    for (const std::size_t v : s.views) s.lists.push_back(std::move(sampled[v]));
  } else {
    std::vector<Frustum> frusta;
    for (const std::size_t v : s.views) frusta.push_back(views[v]);
    if (values.metric == nullptr) {
      s.lists = exact_view_cells(*values.classes, frusta, gain);
      return s;
    }
    s.lists = values.metric->cells(frusta, values.metric->creditable());
    for (const ViewCells& list : s.lists) {
      std::vector<double>& r = s.chance.emplace_back();
      for (const std::uint32_t c : list.cells) {
        r.push_back(gain.surface_rates[surface_class(values.metric->distances()[c])]);
      }
    }
  }
  return s;
}

/// The shortest open tour from the current pose through `members` (shortlist positions).
OpenTour tour_through(const Shortlist& s, std::span<const double> travel,
                      const std::vector<std::size_t>& members) {
  const std::size_t m = s.views.size(), n = members.size();
  std::vector<double> start(n), d(n * n);
  for (std::size_t a = 0; a < n; ++a) {
    start[a] = travel[s.views[members[a]]];
    for (std::size_t b = 0; b < n; ++b) d[a * n + b] = s.between[members[a] * m + members[b]];
  }
  OpenTour t = shortest_open_tour(start, d);
  for (std::size_t& k : t.order) k = members[k];
  return t;
}

/// What the greedy selection has chosen so far (shortlist positions).
struct Selection {
  std::vector<std::size_t> chosen;  ///< in the order added
  std::vector<bool> taken;
  OpenTour tour;               ///< through the chosen, when a travel weight orders them
  std::vector<double> missed;  ///< per compact cell, prod over the chosen of (1 - v)
};

/// J(S + i) - J(S) of every view i not taken, estimated on the sample at `rate` (the single-view
/// values at the first step). Each sum runs in its list's order on one thread: the same for any
/// thread count.
void marginal_values(const Shortlist& s, const CompactCells& compact, const Selection& sel,
                     const std::vector<ViewGain>& gains, double rate, int num_threads,
                     std::vector<double>& marginal) {
  const std::size_t m = s.views.size();
  if (sel.chosen.empty()) {
    for (std::size_t i = 0; i < m; ++i) marginal[i] = gains[s.views[i]].value(s.quantity);
    return;
  }
  run_with_threads(num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, m, [&](std::size_t i) {
      if (sel.taken[i]) return;
      const std::vector<std::uint32_t>& at = compact.at[i];
      const std::vector<double>& seen = s.lists[i].seen;
      double sum = 0.0;
      for (std::size_t k = 0; k < at.size(); ++k) sum += seen[k] * sel.missed[at[k]];
      marginal[i] = rate * sum;
    });
  });
}

/// The greedy selection (docs/decision.md, "Planning a sequence"): up to `config.horizon` views,
/// each the one of highest marginal value less `cost` times its detour, into `plan`.
void select_views(const Shortlist& s, std::span<const double> travel, double cost,
                  const GainConfig& gain, const SequenceConfig& config, SequencePlan& plan) {
  const std::size_t m = s.views.size();
  const double rate = std::ldexp(1.0, config.sample_bits);
  const CompactCells compact(s.lists);
  Selection sel{{}, std::vector<bool>(m, false), {}, std::vector<double>(compact.size, 1.0)};
  std::vector<double> marginal(m, 0.0);
  for (int step = 0; step < config.horizon; ++step) {
    marginal_values(s, compact, sel, plan.gains, rate, gain.num_threads, marginal);
    std::size_t best = m;
    double best_score = -std::numeric_limits<double>::infinity();
    OpenTour best_tour;
    for (std::size_t i = 0; i < m; ++i) {
      if (sel.taken[i]) continue;
      OpenTour t;
      if (sel.chosen.empty()) {
        t = {{i}, travel[s.views[i]]};
      } else if (cost > 0.0) {
        // The tour through the chosen views and this one.
        std::vector<std::size_t> members = sel.chosen;
        members.push_back(i);
        t = tour_through(s, travel, members);
      }
      const double score = marginal[i] - cost * (t.length - sel.tour.length);
      if (score > best_score) {
        best_score = score;
        best = i;
        best_tour = std::move(t);
      }
    }
    // NOTE: after the first view, a view whose marginal value does not pay for its detour
    // shortens the sequence rather than join it.
    if (best == m || (!sel.chosen.empty() && !(best_score > 0.0))) break;
    sel.chosen.push_back(best);
    sel.taken[best] = true;
    plan.value += marginal[best];
    if (!best_tour.order.empty()) sel.tour = std::move(best_tour);
    if (step + 1 < config.horizon) {
      const std::vector<std::uint32_t>& at = compact.at[best];
      const std::vector<double>& seen = s.lists[best].seen;
      for (std::size_t k = 0; k < at.size(); ++k) {
        // NOTE: a surface credit v r is missed with the chance 1 - v, r being the cell's own.
        const double v = s.chance.empty() ? seen[k] : seen[k] / s.chance[best][k];
        sel.missed[at[k]] *= 1.0 - v;
      }
    }
  }
  // With no travel weight the tours above were skipped until the last step; order them now.
  if (sel.tour.order.size() != sel.chosen.size()) sel.tour = tour_through(s, travel, sel.chosen);
  for (const std::size_t i : sel.chosen) plan.chosen.push_back(s.views[i]);
  for (const std::size_t i : sel.tour.order) plan.tour.push_back(s.views[i]);
  plan.tour_length = sel.tour.length;
  plan.first = plan.tour.front();
}

}  // namespace

SequencePlan plan_sequence(const OccupancyGrid& grid, std::span<const Frustum> views,
                           std::span<const double> travel, const GainConfig& gain,
                           const SequenceConfig& config) {
  gain.validate();
  config.validate();
  // NOTE: a sequence ranks by cells: on the cells' classes alone (the survival reading's cells,
  // greedy's count), what count_view_gains and exact_view_cells compute; or by a metric listed
  // cell by cell (the surface model), what MetricEvaluator's gains and cells compute.
  const GainQuantity quantity = method_traits(gain.method).quantity(GainObjective::kCells);
  if (!plans_sequences(gain.method)) {
    throw std::invalid_argument(cat("plan_sequence: gain.method must be survival, greedy or ",
                                    "surface, got ", to_string(gain.method)));
  }
  if (quantity == GainQuantity::kMetric && config.sample_bits > 0) {
    throw std::invalid_argument(
        cat("plan_sequence: ", to_string(gain.method),
            " is evaluated in full; planner.sequence.sample_bits must be 0"));
  }
  if (views.empty()) throw std::invalid_argument("no candidate views to choose from");
  if (travel.size() != views.size()) {
    throw std::invalid_argument(
        cat("plan_sequence: ", views.size(), " views but ", travel.size(), " travel distances"));
  }
  const ClassMap classes(grid);  // what the per-cell lists read
  std::optional<MetricEvaluator> metric;
  Values values{quantity, &classes, nullptr};
  if (quantity == GainQuantity::kMetric) values.metric = &metric.emplace(grid, gain);
  SequencePlan plan;
  std::vector<ViewCells> sampled = single_values(grid, values, views, gain, config, plan.gains);
  double best_value = 0.0;
  for (const ViewGain& g : plan.gains) best_value = std::max(best_value, g.value(quantity));
  // NOTE: relative to the best view, so the weight's meaning does not shrink with the map's
  // unobserved cells.
  const double cost = config.travel_weight * best_value;  // [cells/m]
  for (std::size_t v = 0; v < views.size(); ++v) {
    plan.scores.push_back(plan.gains[v].value(quantity) - cost * travel[v]);
  }
  const Shortlist shortlist =
      shortlist_of(views, values, gain, config, plan.gains, std::move(sampled));
  if (config.horizon > 1) plan.shortlisted = shortlist.views.size();
  select_views(shortlist, travel, cost, gain, config, plan);
  return plan;
}

Plan decide_by_sequence(const OccupancyGrid& grid, std::span<const Candidate> candidates,
                        const PlannerConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<Frustum> views;
  std::vector<double> travel;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    if (!candidates[c].more_views.empty()) {
      throw std::invalid_argument(cat("planner.sequence plans single views; candidate ", c,
                                      " is a sweep of ", candidates[c].more_views.size() + 1,
                                      " views"));
    }
    views.push_back(candidates[c].view);
    travel.push_back(candidates[c].travel);
  }
  GainConfig gain = config.gain;
  gain.method = config.method.gain;
  const SequenceConfig sequence_config = sequence_of(config);
  SequencePlan sequence = plan_sequence(grid, views, travel, gain, sequence_config);
  Plan plan;
  plan.best = sequence.first;
  plan.gains = std::move(sequence.gains);
  plan.scores = std::move(sequence.scores);
  plan.evaluated = candidates.size();
  plan.sequence = std::move(sequence.tour);
  plan.tour_length = sequence.tour_length;
  plan.sequence_value = sequence.value;
  const bool counts = decision_quantity(config) == GainQuantity::kCount;
  const bool sampled = sequence_config.sample_bits > 0;
  if (sampled) plan.estimated.assign(plan.gains.size(), true);
  if (counts) {
    for (const ViewGain& g : plan.gains) plan.greedy_gains.push_back(g.gain);
  }
  plan.seconds = seconds_since(start);
  const bool metric = decision_quantity(config) == GainQuantity::kMetric;  // evaluated exactly
  if ((!counts && !metric) || sampled) {
    // NOTE: the cells decided; the bits of eq. (4) are the chosen view's report (as pruned).
    const auto predict_start = std::chrono::steady_clock::now();
    plan.gains[plan.best] = exact_view_gain(grid, views[plan.best], gain);
    plan.prediction_seconds = seconds_since(predict_start);
    if (sampled) plan.estimated[plan.best] = false;
    if (counts) plan.greedy_gains[plan.best] = plan.gains[plan.best].gain;
  }
  return plan;
}

}  // namespace vantage
