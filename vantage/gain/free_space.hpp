#pragma once
/// @file
/// Where a ray may cross free space many cells at a time (docs/decision.md, "The swept search"):
/// per block of 4^3 cells and per octant of directions, the edge of the largest cube of blocks
/// whose cells are all free that has the block at its corner and reaches out in the octant's
/// directions. A free cell changes nothing on a ray of the survival reading or greedy's count,
/// and a ray only ever moves on in its own octant's directions, so a ray in such a cube may leave
/// it in one step.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "vantage/map/block_census.hpp"
#include "vantage/map/grid_spec.hpp"
#include "vantage/map/traversal.hpp"

namespace vantage {

/// Free cubes of blocks ahead of each block, per octant: octant o's bit a is set when a walk
/// moves towards higher indices on axis a (a walk that never moves on an axis may take either).
struct FreeSpace {
  static constexpr int kShift = 2;
  static constexpr int kBlock = 1 << kShift;  ///< block edge [cells]

  Index3 dims = Index3::Zero();  ///< blocks along each axis
  /// extent[o][b]: 0 when block b holds a cell that is not free; else e >= 1, and every block
  /// b + k (k_a in [0, e - 1] towards octant o's side on each axis a, within the grid) holds free
  /// cells only. Blocks past the grid do not limit it.
  std::array<std::vector<std::uint8_t>, 8> extent;

  bool empty() const { return extent[0].empty(); }
  /// The block that holds `cell`.
  std::size_t block_of(const Index3& cell) const { return BlockCensus::block_of(cell, dims); }
  /// The extent, for octant `octant`, of the block that holds `cell`.
  int extent_at(int octant, const Index3& cell) const {
    return extent[static_cast<std::size_t>(octant)][block_of(cell)];
  }
  /// The cells [lo, hi] of the free cube of extent e >= 1 ahead of `cell`'s block towards
  /// `octant`, cut to the grid of `cell_dims` cells.
  static void cube(const Index3& cell, int octant, int e, const Index3& cell_dims, Index3& lo,
                   Index3& hi) {
    for (int a = 0; a < 3; ++a) {
      const int b = cell[a] >> kShift;
      if ((octant >> a) & 1) {
        lo[a] = b << kShift;
        hi[a] = std::min(cell_dims[a] - 1, ((b + e) << kShift) - 1);
      } else {
        lo[a] = std::max(0, (b - e + 1) << kShift);
        hi[a] = std::min(cell_dims[a] - 1, ((b + 1) << kShift) - 1);
      }
    }
  }

  /// The jump across free space: leaves the free cube ahead of the walk's cell in one step
  /// (GridWalk::leave_box), into the first cell past it, which may lie outside the grid. False,
  /// and no step, when the cell's block is in no cube or the cube holds the walk's end.
  bool cross(GridWalk& walk, const GridSpec& spec) const {
    const int e = extent_at(walk.octant(), walk.cell());
    if (e == 0) return false;
    Index3 lo, hi;
    cube(walk.cell(), walk.octant(), e, spec.dims, lo, hi);
    if ((walk.end().array() >= lo.array()).all() && (walk.end().array() <= hi.array()).all()) {
      return false;
    }
    walk.leave_box(lo, hi);
    return true;
  }
};

/// The free space of a grid, from its census.
FreeSpace free_space(const BlockCensus& census);

}  // namespace vantage
