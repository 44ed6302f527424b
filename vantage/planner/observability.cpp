#include "vantage/planner/observability.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/gain/view_gain.hpp"
#include "vantage/util/text.hpp"

namespace vantage {

std::string AlphaSetting::label() const {
  if (automatic) return "auto";
  std::ostringstream out;
  out.precision(15);  // as scans.csv has always written a: "{:.15g}"
  out << value;
  return out.str();
}

AlphaSetting parse_alpha_setting(std::string_view text, double prior) {
  if (text == "auto") return {true, prior};
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !(value > 0.0 && value <= 1.0)) {
    throw std::invalid_argument(
        cat("alpha must be 'auto' or a number in (0, 1], got '", text, "'"));
  }
  return {false, value};
}

std::vector<double> expected_cells_by_alpha(const OccupancyGrid& grid,
                                            std::span<const Frustum> views, GainConfig config,
                                            std::span<const double> alphas) {
  if (method_traits(config.method).ray == TargetRay::kSurvival) {
    return survival_cells_by_alpha(grid, views, alphas, config.num_threads);
  }
  config.method = GainMethod::kProbabilistic;
  std::vector<double> cells;
  cells.reserve(alphas.size());
  for (const double alpha : alphas) {
    config.alpha = alpha;
    double sum = 0.0;
    for (const ViewGain& g : evaluate_views(grid, views, config)) sum += g.cells;
    cells.push_back(sum);
  }
  return cells;
}

ObservabilityFitConfig survival_fit_config() {
  ObservabilityFitConfig config;
  config.alphas = {0.9, 0.95, 0.98, 0.99, 0.995, 0.998, 0.9995};  // [a per unobserved cell]
  config.prior = kSurvivalAlpha;
  return config;
}

double default_alpha(PlannerMethod method, double literal) {
  return uses_survival_reading(method) ? kSurvivalAlpha : literal;
}

void ObservabilityFitConfig::validate() const {
  if (alphas.size() < 2) {
    throw std::invalid_argument("observability.alphas needs at least two values to fit between");
  }
  for (std::size_t j = 0; j < alphas.size(); ++j) {
    if (!(alphas[j] > 0.0 && alphas[j] < 1.0)) {
      throw std::invalid_argument(
          cat("observability.alphas[", j, "] must lie in (0, 1), got ", alphas[j]));
    }
    if (j > 0 && !(alphas[j] > alphas[j - 1])) {
      throw std::invalid_argument(cat("observability.alphas must ascend, but [", j,
                                      "] = ", alphas[j], " follows ", alphas[j - 1]));
    }
  }
  if (!(prior > 0.0 && prior <= 1.0)) {
    throw std::invalid_argument(cat("observability.prior must lie in (0, 1], got ", prior));
  }
  if (!(recency > 0.0 && recency <= 1.0)) {
    throw std::invalid_argument(cat("observability.recency must lie in (0, 1], got ", recency));
  }
}

ObservabilityFit::ObservabilityFit(ObservabilityFitConfig config) : config_(std::move(config)) {
  config_.validate();
  for (const double a : config_.alphas) x_.push_back(std::log1p(-a));
}

void ObservabilityFit::record(std::span<const double> expected_cells, double actual_cells) {
  if (expected_cells.size() != x_.size()) {
    throw std::invalid_argument(cat("observability fit: ", expected_cells.size(),
                                    " predictions for ", x_.size(), " values of a"));
  }
  if (!(actual_cells >= 0.0 && std::isfinite(actual_cells))) {
    throw std::invalid_argument(
        cat("observability fit: actual cells ", actual_cells, " must be finite and >= 0"));
  }
  Outcome outcome;
  for (std::size_t j = 0; j < x_.size(); ++j) {
    if (!(expected_cells[j] >= 0.0 && std::isfinite(expected_cells[j]))) {
      throw std::invalid_argument(cat("observability fit: expected cells ", expected_cells[j],
                                      " under a = ", config_.alphas[j],
                                      " must be finite and >= 0"));
    }
    outcome.log_expected.push_back(std::log1p(expected_cells[j]));
  }
  outcome.log_actual = std::log1p(actual_cells);
  outcomes_.push_back(std::move(outcome));
}

double ObservabilityFit::error(double alpha) const {
  // The interval of x = ln(1 - a) holding alpha, and where in it (x_ descends as a ascends).
  const double x = std::log1p(-alpha);
  std::size_t j = 0;
  while (j + 2 < x_.size() && x < x_[j + 1]) ++j;
  const double f = std::clamp((x - x_[j]) / (x_[j + 1] - x_[j]), 0.0, 1.0);
  double sum = 0.0;
  for (const Outcome& o : outcomes_) {  // oldest first, so the recency weight applies as it goes
    const double log_e = (1.0 - f) * o.log_expected[j] + f * o.log_expected[j + 1];
    sum = config_.recency * sum + std::abs(log_e - o.log_actual);
  }
  return sum;
}

double ObservabilityFit::alpha() const {
  if (outcomes_.empty()) return config_.prior;
  double best = config_.alphas.front();
  double best_error = error(best);
  for (std::size_t j = 0; j + 1 < x_.size(); ++j) {
    for (int k = 1; k <= kSearchSteps; ++k) {
      const double x = x_[j] + (x_[j + 1] - x_[j]) * k / kSearchSteps;
      const double a = -std::expm1(x);  // 1 - e^x
      const double e = error(a);
      if (e < best_error) {
        best = a;
        best_error = e;
      }
    }
  }
  return best;
}

}  // namespace vantage
