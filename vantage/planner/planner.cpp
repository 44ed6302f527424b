#include "vantage/planner/planner.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "vantage/planner/choose.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

std::vector<ViewGain> gains_of(const OccupancyGrid& grid, std::span<const Candidate> candidates,
                               GainConfig config, GainMethod method) {
  config.method = method;
  std::vector<Frustum> views;
  views.reserve(candidates.size());
  for (const Candidate& c : candidates) views.push_back(c.view);
  return evaluate_views(grid, views, config);
}

std::vector<double> values(const std::vector<ViewGain>& gains) {
  std::vector<double> out;
  out.reserve(gains.size());
  for (const ViewGain& g : gains) out.push_back(g.gain);
  return out;
}

}  // namespace

std::string_view to_string(PlannerMethod method) {
  switch (method) {
    case PlannerMethod::kProbabilistic:
      return "probabilistic";
    case PlannerMethod::kGreedy:
      return "greedy";
    case PlannerMethod::kRandom:
      return "random";
    case PlannerMethod::kLatombe:
      return "latombe";
    case PlannerMethod::kYamauchi:
      return "yamauchi";
  }
  return "unknown";
}

PlannerMethod parse_planner_method(std::string_view name) {
  for (const PlannerMethod m :
       {PlannerMethod::kProbabilistic, PlannerMethod::kGreedy, PlannerMethod::kRandom,
        PlannerMethod::kLatombe, PlannerMethod::kYamauchi}) {
    if (name == to_string(m)) return m;
  }
  throw std::invalid_argument(cat("unknown method '", name,
                                  "' (expected probabilistic, greedy, random, latombe or "
                                  "yamauchi)"));
}

void PlannerConfig::validate() const {
  gain.validate();
  if (!(lambda >= 0.0 && std::isfinite(lambda))) {
    throw std::invalid_argument(cat("planner.lambda must be >= 0, got ", lambda));
  }
}

Plan plan_next_view(const OccupancyGrid& grid, std::span<const Candidate> candidates,
                    const PlannerConfig& config, std::uint64_t seed) {
  config.validate();
  if (candidates.empty()) throw std::invalid_argument("no candidate views to choose from");
  const auto start = std::chrono::steady_clock::now();
  Plan plan;
  const bool probabilistic = config.method == PlannerMethod::kProbabilistic;
  plan.gains = gains_of(grid, candidates, config.gain,
                        probabilistic ? GainMethod::kProbabilistic : GainMethod::kGreedy);
  if (!probabilistic) {
    plan.greedy_gains = values(plan.gains);
  } else if (config.greedy_reference) {
    const auto reference_start = std::chrono::steady_clock::now();
    plan.greedy_gains = values(gains_of(grid, candidates, config.gain, GainMethod::kGreedy));
    plan.reference_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - reference_start).count();
  }

  plan.scores = values(plan.gains);
  switch (config.method) {
    case PlannerMethod::kProbabilistic:
    case PlannerMethod::kGreedy:
      plan.best = choose_best(plan.scores);
      break;
    case PlannerMethod::kRandom:
      plan.best = choose_random(candidates.size(), seed);
      break;
    case PlannerMethod::kLatombe:
      for (std::size_t i = 0; i < candidates.size(); ++i) {
        plan.scores[i] *= std::exp(-config.lambda * candidates[i].travel);
      }
      plan.best = choose_best(plan.scores);
      break;
    case PlannerMethod::kYamauchi:
      for (std::size_t i = 0; i < candidates.size(); ++i) plan.scores[i] = -candidates[i].travel;
      plan.best = choose_best(plan.scores);
      break;
  }
  plan.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return plan;
}

}  // namespace vantage
