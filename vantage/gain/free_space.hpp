#pragma once
/// @file
/// Where a ray may cross free space many cells at a time (docs/decision.md, "The swept search"):
/// per block of 4^3 cells, the Chebyshev radius of the cube of blocks around it whose cells are
/// all free. A free cell changes nothing on a ray of the survival reading or greedy's count, so a
/// ray in such a cube may leave it in one step.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "vantage/map/block_census.hpp"
#include "vantage/map/grid_spec.hpp"

namespace vantage {

/// Free cubes of blocks around each block.
struct FreeSpace {
  static constexpr int kShift = 2;
  static constexpr int kBlock = 1 << kShift;  ///< block edge [cells]

  Index3 dims = Index3::Zero();  ///< blocks along each axis
  /// Per block: 0 when it holds a cell that is not free; else r >= 1, and every block within
  /// Chebyshev distance r - 1 of it (in the grid) holds free cells only.
  std::vector<std::uint8_t> radius;

  /// The radius of the block that holds `cell`.
  std::uint8_t radius_at(const Index3& cell) const {
    return radius[static_cast<std::size_t>(cell.x() >> kShift) +
                  static_cast<std::size_t>(dims.x()) *
                      (static_cast<std::size_t>(cell.y() >> kShift) +
                       static_cast<std::size_t>(dims.y()) *
                           static_cast<std::size_t>(cell.z() >> kShift))];
  }
  /// The cells [lo, hi] of the free cube around `cell`'s block, whose radius is r >= 1, cut to
  /// the grid of `cell_dims` cells.
  void cube(const Index3& cell, int r, const Index3& cell_dims, Index3& lo, Index3& hi) const {
    for (int a = 0; a < 3; ++a) {
      const int b = cell[a] >> kShift;
      lo[a] = std::max(0, (b - (r - 1)) << kShift);
      hi[a] = std::min(cell_dims[a] - 1, ((b + r) << kShift) - 1);
    }
  }
};

/// The free space of a grid, from its census.
FreeSpace free_space(const BlockCensus& census);

}  // namespace vantage
