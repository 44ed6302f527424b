#pragma once
/// @file
/// The greedy occlusion rule, written once: the simple greedy gain (docs/model.md "Baselines"),
/// unknown-space estimation (§4.3.1) and the reference `greedy_visible` all ask it.

#include <Eigen/Core>
#include <cstddef>

#include "vantage/map/occupancy_grid.hpp"
#include "vantage/map/traversal.hpp"

namespace vantage {

/// Whether a cell of this class hides what lies behind it on a ray: it is occupied (p >= 0.6).
inline bool occludes(CellState state) { return state == CellState::kOccupied; }

/// Whether no cell on the ray from `origin` to the centre of `target`, before the target itself,
/// occludes. Cells outside the grid are free (docs/model.md). `state_of(linear)` gives a cell's
/// class, so any view of the grid (the grid, a gain snapshot) can be asked.
template <typename StateOf>
bool line_of_sight(const GridSpec& spec, const Eigen::Vector3d& origin, const Index3& target,
                   StateOf&& state_of) {
  const std::size_t target_linear = spec.linear(target);
  bool clear = true;
  traverse(spec, origin, spec.center(target), [&](const Index3&, std::size_t linear, int) {
    if (linear == target_linear) return false;
    if (occludes(state_of(linear))) {
      clear = false;
      return false;
    }
    return true;
  });
  return clear;
}

/// line_of_sight on the grid itself.
inline bool line_of_sight(const OccupancyGrid& grid, const Eigen::Vector3d& origin,
                          const Index3& target) {
  return line_of_sight(grid.spec(), origin, target,
                       [&](std::size_t linear) { return grid.state(linear); });
}

}  // namespace vantage
