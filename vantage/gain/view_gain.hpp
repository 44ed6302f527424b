#pragma once
/// @file
/// Expected information gain of candidate views (eqs. 1, 3, 4; docs/model.md "One view"): the
/// gain layer's façade `evaluate_views` (its types: types.hpp), which takes the evaluation
/// `GainConfig::evaluation` names: the exact one (exact.hpp, also for `kAuto`) or the fast one
/// (fast.hpp). The ray model both run is `PaperModel` (model.hpp).

#include <span>
#include <vector>

#include "vantage/gain/types.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// Gains of all views, by the evaluation `config.evaluation` names (kAuto: the exact one for the
/// target models, GainEvaluation). The grid is only read.
std::vector<ViewGain> evaluate_views(const OccupancyGrid& grid, std::span<const Frustum> views,
                                     const GainConfig& config);

}  // namespace vantage
