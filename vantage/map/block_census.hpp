#pragma once
/// @file
/// How many cells of each class every block of 4^3 cells holds (docs/decision.md, "The swept
/// search", item 6), kept by OccupancyGrid as its cells change class: what a ray needs to cross
/// whole blocks of free space, read without a pass over the grid.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "vantage/map/cell_state.hpp"
#include "vantage/map/grid_spec.hpp"

namespace vantage {

/// n / d for every n < 2^32 by a multiply and a shift (Granlund and Montgomery, 1994, Thm 4.2):
/// a division costs the census' update more than the rest of it.
class Divider {
 public:
  Divider() = default;
  explicit Divider(std::uint32_t d);
  std::uint32_t operator()(std::uint32_t n) const {
    const std::uint64_t t = (m_ * n) >> 32;  // the multiplier's low word times n, high word
    return static_cast<std::uint32_t>((n + t) >> shift_);
  }

 private:
  std::uint64_t m_ = 1;  ///< the multiplier less 2^32
  int shift_ = 0;
};

/// Per block of kBlock^3 cells, its cells of each class (a block cut by the grid's far faces
/// holds fewer cells).
class BlockCensus {
 public:
  static constexpr int kShift = 2;
  static constexpr int kBlock = 1 << kShift;  ///< block edge [cells]

  BlockCensus() = default;
  /// The census of a grid of `cell_dims` cells, all unobserved.
  explicit BlockCensus(const Index3& cell_dims);

  /// Blocks along each axis of a grid of `cell_dims` cells (a block cut by the far faces counts).
  static Index3 dims_of(const Index3& cell_dims) {
    return (cell_dims.array() + (kBlock - 1)) / kBlock;
  }
  /// Index of the block that holds `cell` among blocks `dims` along each axis, x fastest: the
  /// one layout of every per-block array (the census, FreeSpace, the credit blocks).
  static std::size_t block_of(const Index3& cell, const Index3& dims) {
    return static_cast<std::size_t>(cell.x() >> kShift) +
           static_cast<std::size_t>(dims.x()) *
               (static_cast<std::size_t>(cell.y() >> kShift) +
                static_cast<std::size_t>(dims.y()) * static_cast<std::size_t>(cell.z() >> kShift));
  }

  /// Blocks along each axis.
  const Index3& dims() const { return dims_; }
  std::size_t size() const { return counts_.size(); }
  /// Index of the block that holds `cell`.
  std::size_t block_of(const Index3& cell) const { return block_of(cell, dims_); }
  /// Cells of `state` in block `block` [cells].
  int count(std::size_t block, CellState state) const {
    return counts_[block][static_cast<std::size_t>(state)];
  }
  /// The classes block `block` holds, as class_bit()s.
  std::uint8_t classes(std::size_t block) const {
    const std::array<std::uint8_t, 3>& c = counts_[block];
    return static_cast<std::uint8_t>((c[0] != 0 ? 1 : 0) | (c[1] != 0 ? 2 : 0) |
                                     (c[2] != 0 ? 4 : 0));
  }

  /// The cell of linear index `cell` (of a grid of at most kMaxGridCells) went from class `from`
  /// to class `to` (not thread-safe).
  void move(std::size_t cell, CellState from, CellState to);
  /// Every cell unobserved again.
  void reset();
  /// Bytes it holds.
  std::size_t bytes() const { return counts_.size() * sizeof(counts_[0]); }

 private:
  Index3 cell_dims_ = Index3::Zero();
  Divider by_x_, by_y_;  ///< by the grid's cells along x, along y
  Index3 dims_ = Index3::Zero();
  std::vector<std::array<std::uint8_t, 3>> counts_;  ///< per block: unobserved, free, occupied
};

/// Calls `run(block, first, n)` for each run of a row's cells that lie in one block of
/// BlockCensus::kBlock cells a side, over the rows of the slices [z0, z1) of `spec`'s grid in
/// ascending linear index: `block` the block's index (BlockCensus::block_of, FreeSpace's too),
/// `first` the linear index of the run's first cell, `n` its cells (kBlock; fewer at the grid's
/// far face). What reads a grid block by block, skipping the blocks a census tells it to.
template <typename Run>
void for_block_runs(const GridSpec& spec, int z0, int z1, Run&& run) {
  constexpr int kShift = BlockCensus::kShift, kBlock = BlockCensus::kBlock;
  const auto blocks_x = static_cast<std::size_t>((spec.dims.x() + kBlock - 1) >> kShift);
  const auto blocks_y = static_cast<std::size_t>((spec.dims.y() + kBlock - 1) >> kShift);
  for (int z = z0; z < z1; ++z) {
    for (int y = 0; y < spec.dims.y(); ++y) {
      const std::size_t row = spec.linear(Index3(0, y, z));
      const std::size_t block_row = blocks_x * (static_cast<std::size_t>(y >> kShift) +
                                                blocks_y * static_cast<std::size_t>(z >> kShift));
      for (int x = 0; x < spec.dims.x(); x += kBlock) {
        run(block_row + static_cast<std::size_t>(x >> kShift), row + static_cast<std::size_t>(x),
            std::min(kBlock, spec.dims.x() - x));
      }
    }
  }
}

}  // namespace vantage
