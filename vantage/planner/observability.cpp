#include "vantage/planner/observability.hpp"

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <system_error>

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

void ObservabilityFitConfig::validate() const {
  if (alphas.empty()) throw std::invalid_argument("observability.alphas must not be empty");
  for (std::size_t j = 0; j < alphas.size(); ++j) {
    if (!(alphas[j] > 0.0 && alphas[j] <= 1.0)) {
      throw std::invalid_argument(
          cat("observability.alphas[", j, "] must lie in (0, 1], got ", alphas[j]));
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
  error_.assign(config_.alphas.size(), 0.0);
}

void ObservabilityFit::record(std::span<const double> expected_cells, double actual_cells) {
  if (expected_cells.size() != error_.size()) {
    throw std::invalid_argument(cat("observability fit: ", expected_cells.size(),
                                    " predictions for ", error_.size(), " values of a"));
  }
  if (!(actual_cells >= 0.0 && std::isfinite(actual_cells))) {
    throw std::invalid_argument(
        cat("observability fit: actual cells ", actual_cells, " must be finite and >= 0"));
  }
  for (std::size_t j = 0; j < error_.size(); ++j) {
    if (!(expected_cells[j] >= 0.0 && std::isfinite(expected_cells[j]))) {
      throw std::invalid_argument(cat("observability fit: expected cells ", expected_cells[j],
                                      " under a = ", config_.alphas[j],
                                      " must be finite and >= 0"));
    }
  }
  for (std::size_t j = 0; j < error_.size(); ++j) {
    error_[j] = config_.recency * error_[j] +
                std::abs(std::log((expected_cells[j] + 1.0) / (actual_cells + 1.0)));
  }
  ++outcomes_;
}

double ObservabilityFit::alpha() const {
  if (outcomes_ == 0) return config_.prior;
  std::size_t best = 0;
  for (std::size_t j = 1; j < error_.size(); ++j) {
    if (error_[j] < error_[best]) best = j;
  }
  return config_.alphas[best];
}

}  // namespace vantage
