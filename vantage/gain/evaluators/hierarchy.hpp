#pragma once
/// @file
/// The map's summary by blocks and what it buys the decision (docs/decision.md, "The pruned
/// search"): rays that cross a block of one class in one step (the survival reading's expected
/// cells seen and greedy's count, exactly as cell by cell); bounds.hpp bounds every view's score
/// from the same blocks.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "vantage/gain/snapshot.hpp"
#include "vantage/gain/types.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// Blocks of kBlock^3 cells: which classes each holds, how many unobserved cells, their entropy,
/// and how deep in unobserved space it lies seen from each of the eight octants.
struct ClassBlocks {
  static constexpr int kShift = 3;
  static constexpr int kBlock = 1 << kShift;  ///< block edge [cells]
  /// Bits of `classes`: the block holds a cell of that class.
  static constexpr std::uint8_t kHasUnobserved = class_bit(CellState::kUnobserved),
                                kHasFree = class_bit(CellState::kFree),
                                kHasOccupied = class_bit(CellState::kOccupied);

  /// Coarse blocks of kCoarse^3 cells (kCoarse / kBlock blocks a side), for long jumps.
  static constexpr int kCoarseShift = 4;
  static constexpr int kCoarse = 1 << kCoarseShift;  ///< coarse block edge [cells]

  Index3 dims = Index3::Zero();              ///< blocks along each axis
  std::vector<std::uint8_t> classes;         ///< per block, kHas* bits
  Index3 coarse_dims = Index3::Zero();       ///< coarse blocks along each axis
  std::vector<std::uint8_t> coarse_classes;  ///< per coarse block, kHas* bits of its cells
  std::vector<std::uint32_t> unobserved;     ///< per block, its unobserved cells [cells]
  std::vector<double> entropy;               ///< per block, H(p) summed over them [bits]
  /// Per cell, bit o: a walk that moves only in octant o's directions (bit a set: towards higher
  /// indices on axis a, else lower) reaches the cell from a grid face it can enter by, through
  /// cells that are not occupied. Every ray from outside the grid is such a walk, so a ray of the
  /// survival reading or greedy to a cell whose bit for the ray's octant is clear is blocked: it
  /// sees nothing. When a view's origin lies inside the grid, every bit is that of plain
  /// reachability (6-connected, from the faces and those origins), for every octant.
  std::vector<std::uint8_t> reach;
  /// open[o][b]: block b's unobserved cells with reach bit o [cells]
  std::vector<std::uint32_t> open[8];
  std::vector<std::uint32_t> open_any;  ///< per block, its unobserved cells with any reach bit
  std::vector<double> open_entropy;     ///< per block, H(p) summed over cells with any reach bit
  /// depth[o][b]: the Chebyshev distance in blocks from block b to the nearest block that holds a
  /// known cell or lies outside the grid, among the blocks on octant o's side of b (o's bit a set:
  /// towards higher indices on axis a); 0 when b holds a known cell itself.
  std::vector<std::uint8_t> depth[8];

  std::size_t at(const Index3& b) const {
    return static_cast<std::size_t>(b.x()) +
           static_cast<std::size_t>(dims.x()) *
               (static_cast<std::size_t>(b.y()) +
                static_cast<std::size_t>(dims.y()) * static_cast<std::size_t>(b.z()));
  }
  std::size_t coarse_at(const Index3& b) const {
    return static_cast<std::size_t>(b.x()) +
           static_cast<std::size_t>(coarse_dims.x()) *
               (static_cast<std::size_t>(b.y()) +
                static_cast<std::size_t>(coarse_dims.y()) * static_cast<std::size_t>(b.z()));
  }
  bool is_reachable(std::size_t cell) const { return reach[cell] != 0; }
  /// Bytes it holds.
  std::size_t bytes() const;
};

/// Summarizes a snapshot for rays from the origins of `views` (in parallel; the same for any
/// thread count).
ClassBlocks summarize_classes(const GainMap& map, std::span<const Frustum> views,
                              int num_threads = 0);

/// Every view's `quantity`, a count of cells (counts_classes, types.hpp): the survival reading's
/// expected cells seen (ViewGain::cells; ViewGain::gain is left 0) or greedy's count (both
/// fields); throws std::invalid_argument for another. Each unobserved cell in a view's frustum on
/// its own ray,
/// exactly as exact_view_gains computes ViewGain::cells for the survival reading and greedy (the
/// same cells, the same sums in the same order, so bit for bit). With `blocks` (made for these
/// views), a target no walk of its ray's octant reaches counts 0 uncast, and a ray crosses a
/// block of one class in one step: free costs nothing, occupied ends it, unobserved multiplies by
/// alpha^k (the hierarchical walk); without, it goes cell by cell (the reference).
std::vector<ViewGain> count_view_gains(const GainMap& map, const ClassBlocks* blocks,
                                       std::span<const Frustum> views, GainQuantity quantity,
                                       const GainConfig& config);

}  // namespace vantage
