#pragma once
/// @file
/// Fast gain evaluation (docs/fast-gain.md): rays cast outward through each candidate's frustum,
/// every ray carrying the model's state (docs/model.md "One ray") along itself, and every
/// unobserved cell credited once per view, by the ray that owns it. Its parts: the layout of the
/// rays (fast_layout.hpp), the cast (fast_cast.hpp), the replay and the jump (fast_replay.hpp).

#include <span>
#include <vector>

#include "vantage/gain/fast_layout.hpp"
#include "vantage/gain/model.hpp"
#include "vantage/gain/types.hpp"

namespace vantage {

/// Fast evaluation of every view (GainEvaluation::kFast), whatever `config.evaluation` says. The
/// grid is only read.
///
/// The probabilistic method casts rays; the greedy one has no state to carry along a ray, and an
/// exact line of sight stops at the first occupied cell, so its fast mode is the exact one.
std::vector<ViewGain> fast_view_gains(const OccupancyGrid& grid, std::span<const Frustum> views,
                                      const GainConfig& config);

/// The same on a snapshot taken earlier, with the ray model `Model` (model.hpp); instantiated
/// for PaperModel and BlindModel.
template <typename Model = PaperModel>
std::vector<ViewGain> fast_view_gains(const GainMap& map, std::span<const Frustum> views,
                                      const GainConfig& config);

namespace detail {

/// Casts the rays `plan` laid out (plan_rays) for the probabilistic method; threads as the caller
/// runs it.
std::vector<ViewGain> cast_rays(const FastPlan& plan, const GainMap& map,
                                std::span<const Frustum> views, const GainConfig& config);

}  // namespace detail
}  // namespace vantage
