#include "vantage/map/block_census.hpp"

#include <algorithm>

namespace vantage {

BlockCensus::BlockCensus(const Index3& cell_dims)
    : cell_dims_(cell_dims), dims_((cell_dims.array() + (kBlock - 1)) / kBlock) {
  reset();
}

void BlockCensus::move(std::size_t cell, CellState from, CellState to) {
  const auto nx = static_cast<std::size_t>(cell_dims_.x());
  const auto ny = static_cast<std::size_t>(cell_dims_.y());
  const std::size_t row = cell / nx;
  const Index3 c(static_cast<int>(cell - row * nx), static_cast<int>(row % ny),
                 static_cast<int>(row / ny));
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
