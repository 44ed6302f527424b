#include "vantage/gain/view_gain.hpp"

#include <algorithm>
#include <stdexcept>

#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/evaluators/metric_evaluator.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/util/text.hpp"

namespace vantage {

constexpr EnumNames<GainEvaluation, 2> kEvaluationNames = {
    {{GainEvaluation::kExact, "exact"}, {GainEvaluation::kAuto, "auto"}}};

std::string_view to_string(GainEvaluation evaluation) {
  return name_of(evaluation, kEvaluationNames);
}

GainEvaluation parse_gain_evaluation(std::string_view name) {
  return value_named(name, kEvaluationNames, "gain evaluation");
}

void GainConfig::validate() const {
  if (!(alpha > 0.0 && alpha <= 1.0)) {
    throw std::invalid_argument(cat("gain.alpha must lie in (0, 1], got ", alpha));
  }
  if (!(epsilon >= 0.0 && epsilon < 0.5)) {
    throw std::invalid_argument(cat("gain.epsilon must lie in [0, 0.5), got ", epsilon));
  }
  if (!(ray_spacing > 0.0 && ray_spacing <= 1.0)) {
    throw std::invalid_argument(
        cat("gain.ray_spacing must lie in (0, 1] cells, got ", ray_spacing));
  }
  if (num_threads < 0) {
    throw std::invalid_argument(cat("gain.num_threads must be >= 0, got ", num_threads));
  }
  for (const double r : surface_rates) {
    if (!(r >= 0.0 && r <= 1.0)) {
      throw std::invalid_argument(cat("gain.surface_rates must each lie in [0, 1], got ", r));
    }
  }
}

std::vector<ViewGain> evaluate_views(const OccupancyGrid& grid, std::span<const Frustum> views,
                                     const GainConfig& config) {
  if (is_volumetric_metric(config.method)) return metric_view_gains(grid, views, config);
  return exact_view_gains(grid, views, config);
}

}  // namespace vantage
