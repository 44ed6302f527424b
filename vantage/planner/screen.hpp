#pragma once
/// @file
/// The screened decision (PlannerConfig::search = kScreened; docs/decision.md): the probabilistic
/// method's argmax without every candidate's full evaluation. Nested hashed samples of the
/// unobserved cells (1/64, then 1/16, then 1/4 of them) give each candidate an unbiased estimate
/// of its gain and a bound on its standard error; a candidate whose estimate cannot reach the
/// leader's is dropped; the candidates left are evaluated in full, and the best of them is the
/// decision. Deterministic: the sample is a hash of the cell's index, and every sum runs in a
/// fixed order.

#include <cstddef>
#include <span>
#include <vector>

#include "vantage/gain/view_gain.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage::detail {

/// What the screen found.
struct Screening {
  /// Per candidate: the full evaluation (config.evaluation) where `estimated` is false, else
  /// the sampling estimate of the last stage it took part in (ViewGain::targets estimated too).
  std::vector<ViewGain> gains;
  std::vector<bool> estimated;  ///< per candidate: dropped by the screen, `gains` is an estimate
};

/// Screens the candidates whose views are `frusta[first[c] .. first[c + 1])` and evaluates the
/// survivors in full with `config` (method probabilistic). `cells_objective`: rank by expected
/// cells seen (ViewGain::cells) instead of bits.
Screening screen_candidates(const OccupancyGrid& grid, std::span<const Frustum> frusta,
                            std::span<const std::size_t> first, const GainConfig& config,
                            bool cells_objective);

/// The sampled decision (PlannerConfig::search = kSampled): every candidate's Horvitz-Thompson
/// estimate on the unobserved cells whose hash has its top `bits` bits zero (one in 2^bits, the
/// same cells for every view and method), all flagged estimated. `config.method` must have
/// sampled estimates (methods.hpp).
Screening sample_candidates(const OccupancyGrid& grid, std::span<const Frustum> frusta,
                            std::span<const std::size_t> first, const GainConfig& config, int bits);

}  // namespace vantage::detail
