#pragma once
/// @file
/// Which of a view's rays may credit a cell under a metric whose value is a sum of cell credits
/// (models/metric_cells.hpp; issue 52). Such a metric credits only creditable cells (unobserved,
/// within D of an occupied cell) that a ray's walk reaches, and no walk from the view's origin
/// reaches a cell the occupied cells' shadows hide from it (OctantShadows). So a ray that passes
/// through no block holding a creditable cell the shadows leave open to the origin credits
/// nothing, and where the unobserved cells need not be counted (the race's finalists) it is not
/// walked: the same value to the last bit (the credits of the rays walked, in their order).

#include <cstdint>
#include <span>
#include <vector>

#include "vantage/gain/models/ray_image.hpp"
#include "vantage/gain/octant_shadows.hpp"
#include "vantage/map/grid_spec.hpp"

namespace vantage::detail {

/// The census blocks (BlockCensus::kBlock cells a side) that hold creditable cells.
struct CreditBlocks {
  std::vector<Index3> first;  ///< each block's first cell, in the blocks' order (block_of)
  /// Per block listed: the octants in which at least one of its creditable cells is not shadowed
  /// (OctantShadows::bits clear); 0 when every one is shadowed in every octant.
  std::vector<std::uint8_t> open;
};

/// The blocks of `creditable` (linear indices of cells of `spec`, not occupied).
CreditBlocks credit_blocks(const GridSpec& spec, const OctantShadows& shadows,
                           std::span<const std::uint32_t> creditable);

/// Per ray of `image`'s lattice (row * image.cols + col), 1 where the ray may pass through a
/// block of `blocks` whose creditable cells the shadows do not all hide from the image's origin
/// (the block's cube widened by kCellSpare of a cell and of a ray), else 0: a ray marked 0
/// reaches no creditable cell.
std::vector<std::uint8_t> rays_that_may_credit(const RayImage& image, const GridSpec& spec,
                                               const OctantShadows& shadows,
                                               const CreditBlocks& blocks);

}  // namespace vantage::detail
