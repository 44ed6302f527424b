#include "vantage/planner/types.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "vantage/gain/methods.hpp"
#include "vantage/util/text.hpp"

namespace vantage {

namespace {

/// The rankings other than the best score, each by its name and the gain it ranks when the name
/// stands alone.
struct RankingName {
  Ranking ranking;
  std::string_view name;
  GainMethod gain;
};
constexpr std::array<RankingName, 4> kRankings = {{
    {Ranking::kTravel, "latombe", GainMethod::kGreedy},
    {Ranking::kNearest, "yamauchi", GainMethod::kGreedy},
    {Ranking::kRandom, "random", GainMethod::kGreedy},
    {Ranking::kSequence, "sequence", GainMethod::kSurvival},
}};

const RankingName* ranking_named(std::string_view name) {
  for (const RankingName& r : kRankings) {
    if (r.name == name) return &r;
  }
  return nullptr;
}

}  // namespace

std::string to_string(PlannerMethod method) {
  const std::string gain(to_string(method.gain));
  for (const RankingName& r : kRankings) {
    if (r.ranking != method.ranking) continue;
    return r.gain == method.gain ? std::string(r.name) : cat(r.name, "+", gain);
  }
  return gain;
}

bool uses_survival_reading(PlannerMethod method) {
  return method_traits(method.gain).ray == TargetRay::kSurvival;
}

SequenceConfig sequence_of(const PlannerConfig& config) {
  SequenceConfig sequence = config.sequence;
  if (config.method.ranking == Ranking::kSequence && !sequence.active()) {
    sequence.horizon = kSequenceDefaults.horizon;
    sequence.travel_weight = kSequenceDefaults.travel_weight;
  }
  return sequence;
}

GainQuantity decision_quantity(const PlannerConfig& config) {
  return method_traits(config.method.gain).quantity(config.objective);
}

PlannerMethod parse_planner_method(std::string_view name) {
  const std::size_t plus = name.find('+');
  const RankingName* ranking = ranking_named(name.substr(0, plus));
  if (plus != std::string_view::npos && ranking != nullptr) {
    if (const auto gain = find_gain_method(name.substr(plus + 1))) {
      return {*gain, ranking->ranking};
    }
  } else if (ranking != nullptr) {
    return {ranking->gain, ranking->ranking};
  } else if (const auto gain = find_gain_method(name)) {
    return {*gain, Ranking::kBest};
  }
  std::string names;
  for (const MethodTraits& t : gain_methods()) names += cat(t.name, ", ");
  for (const RankingName& r : kRankings) names += cat(r.name, ", ");
  throw std::invalid_argument(cat("unknown method '", name, "' (expected ", names,
                                  "or RANKING+GAIN, such as latombe+survival)"));
}

GainObjective natural_objective(PlannerMethod method) {
  return uses_survival_reading(method) ? GainObjective::kCells : GainObjective::kBits;
}

PlannerMethod default_planner_method(ViewTask task, bool knows_pose) {
  if (task == ViewTask::kExploration) return PlannerMethod::kSurvival;
  return {GainMethod::kSurface, knows_pose ? Ranking::kTravel : Ranking::kBest};
}

bool ranks_by_gain(PlannerMethod method) {
  return method.ranking != Ranking::kRandom && method.ranking != Ranking::kNearest;
}

bool uses_travel(PlannerMethod method) {
  return method.ranking == Ranking::kTravel || method.ranking == Ranking::kNearest;
}

bool plans_sequences(GainMethod gain) {
  const MethodTraits& traits = method_traits(gain);
  const GainQuantity by_cells = traits.quantity(GainObjective::kCells);
  return counts_classes(by_cells) || (traits.surface_cells && traits.cells != nullptr);
}

bool has_observability(PlannerMethod method) { return method_traits(method.gain).has_objective(); }

void PlannerConfig::validate() const {
  gain.validate();
  if (!(lambda >= 0.0 && std::isfinite(lambda))) {
    throw std::invalid_argument(cat("planner.lambda must be >= 0, got ", lambda));
  }
  if (swept_rays < 1 || swept_rays > 4096) {
    throw std::invalid_argument(cat("planner.swept_rays must lie in [1, 4096], got ", swept_rays));
  }
  sequence.validate();
  if (sequence.active() || method.ranking == Ranking::kSequence) {
    // NOTE: a sequence plans by cells, what the model sees cell by cell (plans_sequences).
    const GainQuantity by_cells = method_traits(method.gain).quantity(GainObjective::kCells);
    if (!plans_sequences(method.gain) ||
        (method.ranking != Ranking::kBest && method.ranking != Ranking::kSequence)) {
      throw std::invalid_argument(
          cat("planner.sequence plans with survival, greedy or surface (sequence, sequence+greedy, "
              "sequence+surface), not ",
              to_string(method)));
    }
    if (decision_quantity(*this) != by_cells) {
      throw std::invalid_argument("planner.sequence ranks survival's views by cells, not bits");
    }
    if (search) {
      throw std::invalid_argument(cat("planner.search: a sequence evaluates its candidates ",
                                      "itself; the ", to_string(*search),
                                      " search does not serve it (leave the search to the "
                                      "default)"));
    }
  }
}

std::vector<std::size_t> Plan::ranking() const {
  std::vector<std::size_t> order(scores.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if ((a == best) != (b == best)) return a == best;
    if (is_estimate(a) != is_estimate(b)) return !is_estimate(a);
    return scores[a] > scores[b];
  });
  return order;
}

}  // namespace vantage
