#include "vantage/planner/types.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "vantage/gain/methods.hpp"
#include "vantage/util/text.hpp"

namespace vantage {

// NOTE: the planner's own strategies, then one per gain method it scores by, named as the gain
// method is (methods.hpp); the rows' order is the order names are listed in messages.
constexpr EnumNames<PlannerMethod, 14> kPlannerMethodNames = {{
    {PlannerMethod::kProbabilistic, "probabilistic"},
    {PlannerMethod::kSurvival, "survival"},
    {PlannerMethod::kGreedy, "greedy"},
    {PlannerMethod::kRandom, "random"},
    {PlannerMethod::kLatombe, "latombe"},
    {PlannerMethod::kYamauchi, "yamauchi"},
    {PlannerMethod::kOcclusionAware, "occlusion-aware"},
    {PlannerMethod::kUnobservedVoxel, "unobserved-voxel"},
    {PlannerMethod::kRearSideVoxel, "rear-side-voxel"},
    {PlannerMethod::kRearSideEntropy, "rear-side-entropy"},
    {PlannerMethod::kProximityCount, "proximity-count"},
    {PlannerMethod::kAverageEntropy, "average-entropy"},
    {PlannerMethod::kAreaFactor, "area-factor"},
    {PlannerMethod::kSequence, "sequence"},
}};

std::string_view to_string(PlannerMethod method) { return name_of(method, kPlannerMethodNames); }

GainMethod gain_method_of(PlannerMethod method) {
  if (method == PlannerMethod::kSequence) return GainMethod::kSurvival;
  // NOTE: random, latombe and yamauchi report (latombe: and weigh) greedy's count.
  return find_gain_method(to_string(method)).value_or(GainMethod::kGreedy);
}

bool uses_survival_reading(PlannerMethod method) {
  return method_traits(gain_method_of(method)).ray == TargetRay::kSurvival;
}

SequenceConfig sequence_of(const PlannerConfig& config) {
  SequenceConfig sequence = config.sequence;
  if (config.method == PlannerMethod::kSequence && !sequence.active()) {
    sequence.horizon = kSequenceDefaults.horizon;
    sequence.travel_weight = kSequenceDefaults.travel_weight;
  }
  return sequence;
}

PlannerMethod parse_planner_method(std::string_view name) {
  return value_named(name, kPlannerMethodNames, "method");
}

std::string_view to_string(GainObjective objective) {
  return objective == GainObjective::kCells ? "cells" : "bits";
}

GainObjective parse_gain_objective(std::string_view name) {
  if (name == "bits") return GainObjective::kBits;
  if (name == "cells") return GainObjective::kCells;
  throw std::invalid_argument(cat("unknown objective '", name, "' (expected bits or cells)"));
}

GainObjective natural_objective(PlannerMethod method) {
  return uses_survival_reading(method) ? GainObjective::kCells : GainObjective::kBits;
}

bool ranks_by_gain(PlannerMethod method) {
  return method != PlannerMethod::kRandom && method != PlannerMethod::kYamauchi;
}

bool has_observability(PlannerMethod method) {
  return method_traits(gain_method_of(method)).has_objective;
}

void PlannerConfig::validate() const {
  gain.validate();
  if (!(lambda >= 0.0 && std::isfinite(lambda))) {
    throw std::invalid_argument(cat("planner.lambda must be >= 0, got ", lambda));
  }
  if (swept_rays < 1 || swept_rays > 4096) {
    throw std::invalid_argument(cat("planner.swept_rays must lie in [1, 4096], got ", swept_rays));
  }
  sequence.validate();
  if (sequence.active() || method == PlannerMethod::kSequence) {
    if (!uses_survival_reading(method) && method != PlannerMethod::kGreedy) {
      throw std::invalid_argument(
          cat("planner.sequence plans with survival, sequence or greedy, not ", to_string(method)));
    }
    if (uses_survival_reading(method) && objective != GainObjective::kCells) {
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
