#include "vantage/experiment/planning_settings.hpp"

#include <bit>

#include "vantage/planner/search.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// Runs `f`, a std::invalid_argument it throws refused as the setting `name`.
template <typename F>
auto as_setting(const char* name, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const SettingError&) {
    throw;
  } catch (const std::invalid_argument& e) {
    throw SettingError(name, e.what());
  }
}

}  // namespace

PlannerMethod PlanningSettings::planner_method() const {
  if (method.empty()) return default_planner_method(task, knows_pose);
  return as_setting("method", [&] { return parse_planner_method(method); });
}

AlphaSetting PlanningSettings::alpha_setting(double literal) const {
  if (alpha.empty()) return {false, literal};
  return as_setting("alpha", [&] { return parse_alpha_setting(alpha, literal); });
}

PlannerConfig PlanningSettings::planner_config(double literal_alpha) const {
  PlannerConfig config;
  config.method = planner_method();
  config.objective = objective.empty()
                         ? natural_objective(config.method)
                         : as_setting("objective", [&] { return parse_gain_objective(objective); });
  config.gain.alpha = alpha_setting(default_alpha(config.method, literal_alpha)).value;
  config.gain.evaluation =
      as_setting("evaluation", [&] { return parse_gain_evaluation(evaluation); });
  if (!search.empty()) {
    config.search = as_setting("search", [&] { return parse_decision_search(search); });
  }
  config.gain.epsilon = epsilon;
  config.gain.num_threads = threads;
  config.lambda = lambda;
  config.sequence.horizon = horizon;
  config.sequence.travel_weight = travel_weight;
  config.sequence.shortlist = shortlist;
  if (sample < 1 || !std::has_single_bit(static_cast<unsigned>(sample))) {
    throw SettingError("sample", cat("must be a power of two >= 1, got ", sample));
  }
  config.sequence.sample_bits = std::countr_zero(static_cast<unsigned>(sample));
  config.swept_rays = swept_rays;
  as_setting("planner", [&] {
    config.validate();
    return 0;
  });
  as_setting("search", [&] { return resolve_decider(config); });
  return config;
}

void request_plan_reference(PlannerConfig& config) {
  const Decider decider = resolve_decider(config);
  config.greedy_reference = decider.search && *decider.search != DecisionSearch::kSwept;
}

}  // namespace vantage
