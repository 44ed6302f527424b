#include "vantage/map/occupancy_grid.hpp"

#include <algorithm>
#include <new>
#include <stdexcept>

#include "vantage/util/text.hpp"

namespace vantage {
namespace {

void require_probability(double p, const char* field) {
  if (!(p > 0.0 && p < 1.0)) {
    throw std::invalid_argument(cat("occupancy.", field, " must lie in (0, 1), got ", p));
  }
}

}  // namespace

void OccupancyParams::validate() const {
  require_probability(p_hit, "p_hit");
  require_probability(p_miss, "p_miss");
  require_probability(p_min, "p_min");
  require_probability(p_max, "p_max");
  if (!(p_hit > 0.5))
    throw std::invalid_argument(cat("occupancy.p_hit must exceed 0.5, got ", p_hit));
  if (!(p_miss < 0.5)) {
    throw std::invalid_argument(cat("occupancy.p_miss must be below 0.5, got ", p_miss));
  }
  if (!(p_min <= p_miss)) {
    throw std::invalid_argument(
        cat("occupancy.p_min (", p_min, ") must not exceed p_miss (", p_miss, ")"));
  }
  if (!(p_max >= p_hit)) {
    throw std::invalid_argument(
        cat("occupancy.p_max (", p_max, ") must not be below p_hit (", p_hit, ")"));
  }
}

OccupancyGrid::OccupancyGrid(const GridSpec& spec, const OccupancyParams& params)
    : spec_(spec), params_(params) {
  spec_.validate();
  params_.validate();
  hit_ = static_cast<float>(logit(params_.p_hit));
  miss_ = static_cast<float>(logit(params_.p_miss));
  min_ = static_cast<float>(logit(params_.p_min));
  max_ = static_cast<float>(logit(params_.p_max));
  free_max_ = static_cast<float>(logit(kFreeMaxProbability));
  occupied_min_ = static_cast<float>(logit(kOccupiedMinProbability));
  try {
    log_odds_.assign(spec_.num_cells(), 0.0f);
    census_ = BlockCensus(spec_.dims);
    classes_ = CellClasses(spec_.num_cells());
  } catch (const std::bad_alloc&) {
    throw std::length_error(cat("grid of ", spec_.num_cells(), " cells (",
                                spec_.num_cells() * sizeof(float) >> 20,
                                " MiB) does not fit in memory"));
  }
}

void OccupancyGrid::set_probability(std::size_t i, double p) {
  require_probability(p, "cell probability");
  set_log_odds(i, static_cast<float>(logit(p)));
}

void OccupancyGrid::reset() {
  std::fill(log_odds_.begin(), log_odds_.end(), 0.0f);
  census_.reset();
  classes_.reset();
}

CellCounts OccupancyGrid::counts() const {
  CellCounts counts;
  for (std::size_t b = 0; b < census_.size(); ++b) {
    counts.unobserved += static_cast<std::size_t>(census_.count(b, CellState::kUnobserved));
    counts.free += static_cast<std::size_t>(census_.count(b, CellState::kFree));
    counts.occupied += static_cast<std::size_t>(census_.count(b, CellState::kOccupied));
  }
  return counts;
}

}  // namespace vantage
