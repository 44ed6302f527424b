#pragma once
/// @file
/// The swept search's last round (docs/decision.md, "The swept search"): a race between a few
/// finalists on nested hashed samples of the unobserved cells, each sample twice the one
/// before, up to all of them. Every finalist's per-target visibilities on the same cells give
/// each pair's difference and its sampling error; a finalist the leader beats by three standard
/// errors drops out; the race ends with one left or on the full lists, which are exact.

#include <cstddef>
#include <span>
#include <vector>

#include "vantage/gain/class_map.hpp"
#include "vantage/gain/view_gain.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage::detail {

/// How a race ended.
struct Race {
  std::size_t winner = 0;  ///< index among the finalists
  /// Per finalist: its last estimate of the score (exact when `exact`) [cells, times `factor`].
  std::vector<double> scores;
  int bits = 0;        ///< the last sample: one unobserved cell in 2^bits
  bool exact = false;  ///< the race reached the full lists: `winner` is the exact argmax
};

/// Races the finalists whose views are `frusta[first[k] .. first[k + 1])`, each scored by the sum
/// of its views' v_M under `config.method` (survival or greedy) times `factor[k]`, from the
/// smallest sample expected to hold at most `max_sample` unobserved cells (unobserved_by_sample).
/// Deterministic; the same for any thread count.
Race race_candidates(const ClassMap& map, std::span<const Frustum> frusta,
                     std::span<const std::size_t> first, std::span<const double> factor,
                     const GainConfig& config, std::size_t max_sample);

}  // namespace vantage::detail
