#pragma once
/// @file
/// An upper bound on every view's score from the map's block summary alone (hierarchy.hpp;
/// docs/decision.md, "The bound"): what lets the pruned search skip a candidate without
/// evaluating it.

#include <span>
#include <vector>

#include "vantage/gain/evaluators/hierarchy.hpp"
#include "vantage/gain/snapshot.hpp"
#include "vantage/map/grid_spec.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// An upper bound on each view's `quantity` (types.hpp), from the blocks its frustum may touch:
/// their unobserved cells (reachable ones, but for the paper's model, whose visibility never
/// reaches 0), each weighted for kSurvivalCells by alpha^n with n a lower bound on the unobserved
/// cells before it on any ray from the view's origin (its depth in unobserved space on the
/// origin's side); in bits, their H(p) (a target's eq. (4) gain is at most its H(p)); for
/// kPaperCells any per-target value in [0, 1]. The views must be among those `blocks` was made
/// for. Throws std::invalid_argument for a metric's value, which no block bounds.
std::vector<double> view_upper_bounds(const ClassBlocks& blocks, const GridSpec& spec,
                                      const GainMap& map, std::span<const Frustum> views,
                                      GainQuantity quantity, double alpha);

}  // namespace vantage
