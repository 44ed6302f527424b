#pragma once
/// @file
/// The occlusion test shared by unknown-space estimation (§4.3.1) and the simple greedy gain.

#include <Eigen/Core>
#include <cstddef>

#include "vantage/map/occupancy_grid.hpp"
#include "vantage/map/traversal.hpp"

namespace vantage {

/// Whether no cell on the ray from `origin` to the centre of `target`, before the target itself,
/// is occupied. Cells outside the grid are free (MODEL.md).
inline bool line_of_sight(const OccupancyGrid& grid, const Eigen::Vector3d& origin,
                          const Index3& target) {
  const std::size_t target_linear = grid.spec().linear(target);
  bool clear = true;
  traverse(grid.spec(), origin, grid.spec().center(target),
           [&](const Index3&, std::size_t linear, int) {
             if (linear == target_linear) return false;
             if (grid.state(linear) == CellState::kOccupied) {
               clear = false;
               return false;
             }
             return true;
           });
  return clear;
}

/// Upper bound on the lattice steps from `origin` to any cell of the grid, plus one.
inline int max_ray_cells(const GridSpec& spec, const Eigen::Vector3d& origin) {
  const Eigen::Vector3d lo = (spec.origin - origin).cwiseAbs();
  const Eigen::Vector3d hi = (spec.max_corner() - origin).cwiseAbs();
  return static_cast<int>(lo.cwiseMax(hi).sum() / spec.resolution) + 4;
}

}  // namespace vantage
