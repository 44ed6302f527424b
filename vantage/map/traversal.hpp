#pragma once
/// @file
/// Exact 6-connected grid traversal (Amanatides & Woo, 1987) between two points, clipped to the
/// grid, as a visitor that can stop early.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <limits>
#include <type_traits>

#include "vantage/map/grid_spec.hpp"

namespace vantage {

/// What one traversal did.
struct TraversalResult {
  /// Lattice cells the segment crossed before it entered the grid. They are not visited; MODEL.md
  /// counts them as free. When the segment never enters the grid, every cell it crosses counts.
  int skipped = 0;
  int visited = 0;           ///< grid cells handed to the visitor
  bool entered = false;      ///< the segment enters the grid at all
  bool stopped = false;      ///< the visitor asked to stop
  bool reached_end = false;  ///< the cell holding `to` lies in the grid and was visited
};

/// Number of lattice cells a 6-connected traversal from cell a to cell b visits.
inline int lattice_cells_between(const Index3& a, const Index3& b) {
  return (b - a).cwiseAbs().sum() + 1;
}

/// Visits, in order, the grid cells that the segment from `from` to `to` crosses.
///
/// The walk runs on the grid's lattice extended to all of space and is exact: every cell the
/// segment passes through with positive length is visited once, consecutive cells share a face,
/// and where the segment runs exactly through an edge or a corner one of the touching cells is
/// visited as the step between them. The walk takes exactly |Δi| + |Δj| + |Δk| steps from the
/// cell of `from` to the cell of `to`, so it always ends in the cell of `to`.
///
/// Cells outside the grid are never visited. Those before the entry are counted in
/// `TraversalResult::skipped` in O(1) (the walk jumps to the entry cell); the walk ends where the
/// segment leaves the grid.
///
/// @param visit  `bool(const Index3& cell, std::size_t linear, int m)` or the same returning void;
///               `m` is the cell's position along the whole segment from `from` (c_m of MODEL.md).
///               Returning false stops the walk.
template <typename Visitor>
TraversalResult traverse(const GridSpec& spec, const Eigen::Vector3d& from,
                         const Eigen::Vector3d& to, Visitor&& visit) {
  TraversalResult result;
  const Index3 first = spec.lattice_index(from);
  const Index3 last = spec.lattice_index(to);
  const Eigen::Vector3d dir = to - from;

  // Slab clip of the segment to the grid's box.
  double t_enter = 0.0;
  double t_exit = 1.0;
  const Eigen::Vector3d lo = spec.origin;
  const Eigen::Vector3d hi = spec.max_corner();
  for (int a = 0; a < 3; ++a) {
    if (dir[a] == 0.0) {
      if (from[a] < lo[a] || from[a] >= hi[a]) t_exit = -1.0;
      continue;
    }
    double t0 = (lo[a] - from[a]) / dir[a];
    double t1 = (hi[a] - from[a]) / dir[a];
    if (t0 > t1) std::swap(t0, t1);
    t_enter = std::max(t_enter, t0);
    t_exit = std::min(t_exit, t1);
  }
  const int total = lattice_cells_between(first, last);
  if (t_enter > t_exit) {  // misses the box
    result.skipped = total;
    return result;
  }

  Index3 step = Index3::Zero();
  Index3 remaining = Index3::Zero();
  Eigen::Vector3d t_max = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d t_delta = t_max;
  for (int a = 0; a < 3; ++a) {
    const int delta = last[a] - first[a];
    remaining[a] = std::abs(delta);
    if (delta == 0) continue;
    step[a] = delta > 0 ? 1 : -1;
    t_delta[a] = spec.resolution / std::abs(dir[a]);
    const double boundary = spec.origin[a] + (first[a] + (step[a] > 0 ? 1 : 0)) * spec.resolution;
    t_max[a] = (boundary - from[a]) / dir[a];
  }

  // Jump to the entry cell: the cell holding the entry point, pulled onto the grid where rounding
  // put it a hair outside, and never past the segment's own index range.
  Index3 cell = first;
  if (!spec.contains(first)) {
    const Index3 entry_cell = spec.lattice_index(from + t_enter * dir)
                                  .cwiseMax(Index3::Zero())
                                  .cwiseMin(spec.dims - Index3::Ones());
    for (int a = 0; a < 3; ++a) {
      const int advanced = std::clamp((entry_cell[a] - first[a]) * step[a], 0, remaining[a]);
      cell[a] = first[a] + advanced * step[a];
      remaining[a] -= advanced;
      t_max[a] += advanced * t_delta[a];
      result.skipped += advanced;
    }
    if (!spec.contains(cell)) {
      result.skipped = total;
      return result;
    }
  }
  result.entered = true;

  const std::array<std::ptrdiff_t, 3> stride = {
      1, spec.dims.x(), static_cast<std::ptrdiff_t>(spec.dims.x()) * spec.dims.y()};
  auto linear = static_cast<std::ptrdiff_t>(spec.linear(cell));
  int m = result.skipped;
  for (;;) {
    ++result.visited;
    if constexpr (std::is_void_v<decltype(visit(cell, std::size_t{}, m))>) {
      visit(cell, static_cast<std::size_t>(linear), m);
    } else if (!visit(cell, static_cast<std::size_t>(linear), m)) {
      result.stopped = true;
      return result;
    }
    // Next axis: the nearest boundary among the axes that still have steps to take.
    int axis = -1;
    double best = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      if (remaining[a] > 0 && (axis < 0 || t_max[a] < best)) {
        axis = a;
        best = t_max[a];
      }
    }
    if (axis < 0) {
      result.reached_end = true;
      return result;
    }
    cell[axis] += step[axis];
    if (cell[axis] < 0 || cell[axis] >= spec.dims[axis]) return result;  // left the grid
    linear += step[axis] * stride[static_cast<std::size_t>(axis)];
    t_max[axis] += t_delta[axis];
    --remaining[axis];
    ++m;
  }
}

}  // namespace vantage
