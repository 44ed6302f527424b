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

/// What a bound bounds.
enum class BoundKind {
  kSurvivalCells,  ///< the survival reading's expected cells seen [cells]
  kCount,          ///< greedy's count [cells]
  kAllCells,       ///< any per-target value in [0, 1], such as the paper's v_M [cells]
  kSurvivalBits,   ///< the survival reading's eq. (4) gain, at most H(p) of a reachable cell [bits]
  kEntropy,        ///< any per-target gain at most H(p), such as the paper's eq. (4) [bits]
};

/// An upper bound on each view's sum, from the blocks its frustum may touch: their unobserved
/// cells (reachable ones, but for kEntropy and kAllCells), each weighted for kSurvivalCells by
/// alpha^n with n a lower bound on the unobserved cells before it on any ray from the view's origin
/// (its depth in unobserved space on the origin's side). The views must be among those `blocks` was
/// made for.
std::vector<double> view_upper_bounds(const ClassBlocks& blocks, const GridSpec& spec,
                                      const GainMap& map, std::span<const Frustum> views,
                                      BoundKind kind, double alpha);

}  // namespace vantage
