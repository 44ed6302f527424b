#include "vantage/gain/models/credit_rays.hpp"

#include <algorithm>

#include "vantage/gain/models/metric_cells.hpp"
#include "vantage/map/block_census.hpp"

namespace vantage::detail {
namespace {

constexpr int kShift = BlockCensus::kShift, kBlock = BlockCensus::kBlock;

Index3 blocks_across(const GridSpec& spec) { return (spec.dims.array() + (kBlock - 1)) / kBlock; }

}  // namespace

CreditBlocks credit_blocks(const GridSpec& spec, const OctantShadows& shadows,
                           std::span<const std::uint32_t> creditable) {
  const Index3 across = blocks_across(spec);
  const auto n = static_cast<std::size_t>(across.x()) * static_cast<std::size_t>(across.y()) *
                 static_cast<std::size_t>(across.z());
  // NOTE: bit 0x100 marks a block that holds a creditable cell, whatever its shadows.
  std::vector<std::uint16_t> open(n, 0);
  for (const std::uint32_t i : creditable) {
    const Index3 c = spec.unravel(i);
    const std::size_t b =
        static_cast<std::size_t>(c.x() >> kShift) +
        static_cast<std::size_t>(across.x()) *
            (static_cast<std::size_t>(c.y() >> kShift) +
             static_cast<std::size_t>(across.y()) * static_cast<std::size_t>(c.z() >> kShift));
    open[b] |= static_cast<std::uint16_t>(0x100 | static_cast<std::uint8_t>(~shadows.bits(c)));
  }
  CreditBlocks out;
  for (std::size_t b = 0; b < n; ++b) {
    if (open[b] == 0) continue;
    out.blocks.push_back(static_cast<std::uint32_t>(b));
    out.open.push_back(static_cast<std::uint8_t>(open[b] & 0xff));
  }
  return out;
}

std::vector<std::uint8_t> rays_that_may_credit(const RayImage& image, const GridSpec& spec,
                                               const OctantShadows& shadows,
                                               const CreditBlocks& blocks) {
  std::vector<std::uint8_t> out(
      static_cast<std::size_t>(image.rows) * static_cast<std::size_t>(image.cols), 0);
  const Index3 across = blocks_across(spec);
  const std::uint8_t open = shadows.open_octants(image.origin);
  for (std::size_t k = 0; k < blocks.blocks.size(); ++k) {
    std::size_t b = blocks.blocks[k];
    Index3 lo;
    lo.x() = static_cast<int>(b % static_cast<std::size_t>(across.x())) << kShift;
    b /= static_cast<std::size_t>(across.x());
    lo.y() = static_cast<int>(b % static_cast<std::size_t>(across.y())) << kShift;
    lo.z() = static_cast<int>(b / static_cast<std::size_t>(across.y())) << kShift;
    const Index3 hi = (lo.array() + (kBlock - 1)).min(spec.dims.array() - 1);
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
