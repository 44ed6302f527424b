#pragma once
/// @file
/// Expected information gain of candidate views (eqs. 1, 3, 4; docs/model.md "One view"): the
/// gain layer's façade `evaluate_views` (its types: types.hpp), which runs the target models'
/// exact evaluation (exact.hpp) or a metric's rays (evaluators/metric_evaluator.hpp).

#include <span>
#include <vector>

#include "vantage/gain/types.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// Gains of all views under `config.method`, at the ray pitch `config.evaluation` names for a
/// metric (GainEvaluation). The grid is only read.
std::vector<ViewGain> evaluate_views(const OccupancyGrid& grid, std::span<const Frustum> views,
                                     const GainConfig& config);

}  // namespace vantage
