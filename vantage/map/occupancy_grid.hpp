#pragma once
/// @file
/// A dense occupancy grid in log-odds, updated as OctoMap does (docs/model.md, "Cells and their
/// states").

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "vantage/map/block_census.hpp"
#include "vantage/map/cell_classes.hpp"
#include "vantage/map/cell_state.hpp"
#include "vantage/map/grid_spec.hpp"

namespace vantage {

/// log(p / (1 - p)).
inline double logit(double p) { return std::log(p / (1.0 - p)); }
/// 1 / (1 + exp(-l)).
inline double logistic(double l) { return 1.0 / (1.0 + std::exp(-l)); }

/// Sensor-model parameters of the log-odds update (OctoMap's hit/miss/clamp scheme).
struct OccupancyParams {
  double p_hit = 0.7;   ///< probability a hit adds, as logit(p_hit)
  double p_miss = 0.4;  ///< probability a miss adds, as logit(p_miss)
  double p_min = 0.12;  ///< lower clamp; also the occupancy of cells outside the grid
  double p_max = 0.97;  ///< upper clamp

  /// Throws std::invalid_argument naming the field: all in (0, 1), p_min < p_miss < 0.5 < p_hit <
  /// p_max.
  void validate() const;
};

/// How many cells are in each class.
struct CellCounts {
  std::size_t unobserved = 0;
  std::size_t free = 0;
  std::size_t occupied = 0;
};

/// Dense grid of float log-odds, 0 (p = 0.5) meaning unknown.
///
/// Classification works on the stored log-odds against float thresholds, so that a single miss
/// at p_miss = 0.4 lands exactly on the free side, as docs/model.md says it must.
class OccupancyGrid {
 public:
  /// Validates both arguments; throws std::invalid_argument (or std::length_error when the grid
  /// cannot be allocated) with a message that names the problem.
  explicit OccupancyGrid(const GridSpec& spec, const OccupancyParams& params = {});

  const GridSpec& spec() const { return spec_; }
  const OccupancyParams& params() const { return params_; }
  std::size_t size() const { return log_odds_.size(); }

  float log_odds(std::size_t i) const { return log_odds_[i]; }
  double probability(std::size_t i) const { return logistic(log_odds_[i]); }
  CellState state(std::size_t i) const { return state_of(log_odds_[i]); }
  bool is_unobserved(std::size_t i) const { return state(i) == CellState::kUnobserved; }

  /// Class of a stored log-odds value.
  CellState state_of(float l) const {
    if (l <= free_max_) return CellState::kFree;
    if (l >= occupied_min_) return CellState::kOccupied;
    return CellState::kUnobserved;
  }

  // NOTE: writes are not thread-safe, not even to different cells: they keep the census and
  // the packed classes.
  void hit(std::size_t i) { store(i, clamp(log_odds_[i] + hit_)); }
  void miss(std::size_t i) { store(i, clamp(log_odds_[i] + miss_)); }
  void set_log_odds(std::size_t i, float l) { store(i, clamp(l)); }
  void set_probability(std::size_t i, double p);
  /// Every cell back to unknown.
  void reset();

  std::span<const float> log_odds() const { return log_odds_; }
  /// How many cells are in each class, from the census.
  CellCounts counts() const;
  /// Per block of cells, its cells of each class, kept as the cells change.
  const BlockCensus& census() const { return census_; }
  /// Every cell's class, kept as the cells change.
  const CellClasses& classes() const { return classes_; }

 private:
  float clamp(float l) const { return l < min_ ? min_ : (l > max_ ? max_ : l); }
  void store(std::size_t i, float l) {
    const CellState from = state_of(log_odds_[i]), to = state_of(l);
    log_odds_[i] = l;
    if (from != to) {
      census_.move(i, from, to);
      classes_.set(i, to);
    }
  }

  GridSpec spec_;
  OccupancyParams params_;
  float hit_, miss_, min_, max_;
  float free_max_, occupied_min_;
  std::vector<float> log_odds_;
  BlockCensus census_;
  CellClasses classes_;
};

}  // namespace vantage
