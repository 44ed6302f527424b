#include "vantage/map/block_census.hpp"

#include <algorithm>
#include <bit>

namespace vantage {

Divider::Divider(std::uint32_t d) {
  // l = ceil(log2 d); the multiplier floor(2^(32 + l) / d) + 1 lies in (2^32, 2^33]: n / d is
  // (n + (m n >> 32)) >> l with m = floor(2^32 (2^l - d) / d) + 1 < 2^32.
  const int l = d <= 1 ? 0 : static_cast<int>(std::bit_width(d - 1));
  shift_ = l;
  m_ = (((std::uint64_t{1} << l) - d) << 32) / d + 1;
}

BlockCensus::BlockCensus(const Index3& cell_dims)
    : cell_dims_(cell_dims),
      by_x_(static_cast<std::uint32_t>(cell_dims.x())),
      by_y_(static_cast<std::uint32_t>(cell_dims.y())),
      dims_(dims_of(cell_dims)) {
  reset();
}

void BlockCensus::move(std::size_t cell, CellState from, CellState to) {
  const auto i = static_cast<std::uint32_t>(cell);
  const std::uint32_t row = by_x_(i), z = by_y_(row);
  const Index3 c(static_cast<int>(i - row * static_cast<std::uint32_t>(cell_dims_.x())),
                 static_cast<int>(row - z * static_cast<std::uint32_t>(cell_dims_.y())),
                 static_cast<int>(z));
  std::array<std::uint8_t, 3>& counts = counts_[block_of(c)];
  --counts[static_cast<std::size_t>(from)];
  ++counts[static_cast<std::size_t>(to)];
}

void BlockCensus::reset() {
  counts_.assign(static_cast<std::size_t>(dims_.prod()), {0, 0, 0});
  Index3 b;
  for (b.z() = 0; b.z() < dims_.z(); ++b.z()) {
    for (b.y() = 0; b.y() < dims_.y(); ++b.y()) {
      for (b.x() = 0; b.x() < dims_.x(); ++b.x()) {
        // The block's cells inside the grid.
        const Index3 size = (cell_dims_ - b * kBlock).cwiseMin(Index3::Constant(kBlock));
        counts_[block_of(b * kBlock)][0] = static_cast<std::uint8_t>(size.prod());
      }
    }
  }
}

}  // namespace vantage
