#include "vantage/gain/models/credit_rays.hpp"

#include <algorithm>

#include "vantage/gain/models/metric_cells.hpp"
#include "vantage/map/block_census.hpp"

namespace vantage::detail {

CreditBlocks credit_blocks(const GridSpec& spec, const OctantShadows& shadows,
                           std::span<const std::uint32_t> creditable) {
  const Index3 across = BlockCensus::dims_of(spec.dims);
  // NOTE: bit 0x100 marks a block that holds a creditable cell, whatever its shadows.
  std::vector<std::uint16_t> open(static_cast<std::size_t>(across.prod()), 0);
  for (const std::uint32_t i : creditable) {
    const Index3 c = spec.unravel(i);
    open[BlockCensus::block_of(c, across)] |=
        static_cast<std::uint16_t>(0x100 | static_cast<std::uint8_t>(~shadows.bits(c)));
  }
  CreditBlocks out;
  std::size_t b = 0;
  for (int z = 0; z < across.z(); ++z) {
    for (int y = 0; y < across.y(); ++y) {
      for (int x = 0; x < across.x(); ++x, ++b) {
        if (open[b] == 0) continue;
        out.first.push_back(BlockCensus::kBlock * Index3(x, y, z));
        out.open.push_back(static_cast<std::uint8_t>(open[b] & 0xff));
      }
    }
  }
  return out;
}

std::vector<std::uint8_t> rays_that_may_credit(const RayImage& image, const GridSpec& spec,
                                               const OctantShadows& shadows,
                                               const CreditBlocks& blocks) {
  std::vector<std::uint8_t> out(
      static_cast<std::size_t>(image.rows) * static_cast<std::size_t>(image.cols), 0);
  const std::uint8_t open = shadows.open_octants(image.origin);
  for (std::size_t k = 0; k < blocks.first.size(); ++k) {
    const Index3& lo = blocks.first[k];
    const Index3 hi = (lo.array() + (BlockCensus::kBlock - 1)).min(spec.dims.array() - 1);
    // NOTE: every creditable cell of the block hidden (OctantShadows::hides): the octants of the
    // walks to any of its cells, each open at the origin, in none of which one is unshadowed.
    const std::uint8_t need = shadows.octants(image.origin, lo, hi);
    if ((need & open) == need && (blocks.open[k] & need) == 0) continue;
    const Eigen::Vector3d low = spec.origin + spec.resolution * lo.cast<double>();
    const Eigen::Vector3d high =
        spec.origin + spec.resolution * (hi.array() + 1).cast<double>().matrix();
    const Eigen::Vector3d half = (0.5 * (high - low)).array() + kCellSpare * spec.resolution;
    int row_lo, row_hi, col_lo, col_hi;
    if (!image.rays_through_box(0.5 * (low + high), half, kCellSpare, row_lo, row_hi, col_lo,
                                col_hi)) {
      continue;
    }
    for (int row = row_lo; row <= row_hi; row += image.step) {
      std::uint8_t* line = out.data() + static_cast<std::size_t>(row) * image.cols;
      for (int col = col_lo; col <= col_hi; col += image.step) line[col] = 1;
    }
  }
  return out;
}

}  // namespace vantage::detail
