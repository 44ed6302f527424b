#pragma once
/// @file
/// The swept search's last round (docs/decision.md, "The swept search"): a race between a few
/// finalists (under the paper's model, every candidate) on nested hashed samples of the
/// unobserved cells, each sample twice the one before, up to all of them. Every finalist's
/// per-target visibilities on the same cells give each pair's difference and its sampling error;
/// a finalist drops out once the leader is, by three standard errors, no worse than it less a
/// tolerance; the race ends with one left or on the full lists, which are exact.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "vantage/gain/class_map.hpp"
#include "vantage/gain/evaluators/view_cells.hpp"
#include "vantage/gain/types.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage::detail {

/// How a race ended.
struct Race {
  std::size_t winner = 0;  ///< index among the finalists
  /// Per finalist: its last estimate of the score (exact when `exact`) [cells, times `factor`].
  std::vector<double> scores;
  int bits = 0;        ///< the last sample: one unobserved cell in 2^bits
  bool exact = false;  ///< the race reached the full lists: `winner` is the exact argmax
  /// When it stopped short of the full lists with more than one finalist left (`most_new_targets`),
  /// those (indices among the finalists, ascending); `winner` is then the leader on the last
  /// sample. Else empty.
  std::vector<std::size_t> alive;
};

/// Lists the targets of `views` among `cells` (unobserved, ascending) with their values, as
/// exact_view_cells and paper_view_cells do: the same lists for any thread count. `which` holds
/// each view's index among the race's frusta, so that a lister may keep what it learnt of a view
/// across the rounds.
using TargetLister = std::function<std::vector<ViewCells>(std::span<const Frustum> views,
                                                          std::span<const std::size_t> which,
                                                          std::span<const std::uint32_t> cells)>;

/// How a race decides (race_candidates).
struct RaceRules {
  /// A finalist drops out when the leader's score, less `standard_errors` standard errors of
  /// their difference, exceeds its score less `tolerance` times the leader's: 0 asks for the
  /// exact argmax (statistically, before the full lists), 0.005 for a winner within 0.5 % of the
  /// best.
  double tolerance = 0.0;
  double standard_errors = 3.0;
  /// Whether the error of a difference counts one more target the sample may have missed: the
  /// largest value a target of any boost has been listed with, at that boost's weight, times the
  /// largest factor. For values that sit on few targets, where a sample that misses the large ones
  /// gives an estimate and an error both too small.
  bool unseen = false;
  /// > 0: the race stops before a sample whose new cells are expected to put more targets than
  /// this in each finalist's lists (ViewCells::targets of the last sample, a view, times the next
  /// sample's new cells over the last's), leaving the finalists still in it to the caller
  /// (Race::alive).
  double most_new_targets = 0.0;
  /// Per cell of the map, the boost of the samples (cells_by_sample, at most kMostBoost): a cell
  /// of boost o is in the sample of b bits with chance 2^-max(0, b - o), and weighed by its
  /// inverse; empty: none.
  std::span<const std::uint8_t> boost = {};
};

/// Races the finalists whose views are `frusta[first[k] .. first[k + 1])`, each scored by the sum
/// of its views' target values from `list` times `factor[k]`, on the nested samples `levels`
/// (unobserved_by_sample, cells_by_sample: `levels[b]` the cells new in the sample of one in 2^b),
/// from the smallest, by `rules`. Deterministic; the same for any thread count.
Race race_candidates(const std::vector<std::vector<std::uint32_t>>& levels,
                     std::span<const Frustum> frusta, std::span<const std::size_t> first,
                     std::span<const double> factor, const TargetLister& list,
                     const RaceRules& rules = {});

/// The race of the survival reading's or greedy's v_M (`config.method`, exact_view_cells) from the
/// smallest sample expected to hold at most `max_sample` unobserved cells.
Race race_candidates(const ClassMap& map, std::span<const Frustum> frusta,
                     std::span<const std::size_t> first, std::span<const double> factor,
                     const GainConfig& config, std::size_t max_sample, double tolerance = 0.0);

}  // namespace vantage::detail
