#include "vantage/gain/models/reach_codes.hpp"

namespace vantage::detail {

std::vector<std::uint8_t> near_occupied_blocks(const BlockCensus& census) {
  static_assert(BlockCensus::kBlock == FreeSpace::kBlock &&
                2 * FreeSpace::kBlock - 3 > kProximityCells);
  const Index3 d = census.dims();
  const auto block = [&](int x, int y, int z) {
    return static_cast<std::size_t>(x) +
           static_cast<std::size_t>(d.x()) *
               (static_cast<std::size_t>(y) + static_cast<std::size_t>(d.y()) * z);
  };
  std::vector<std::uint8_t> near(static_cast<std::size_t>(d.prod()), 0);
  Index3 c;
  for (c.z() = 0; c.z() < d.z(); ++c.z()) {
    for (c.y() = 0; c.y() < d.y(); ++c.y()) {
      for (c.x() = 0; c.x() < d.x(); ++c.x()) {
        if (!(census.classes(block(c.x(), c.y(), c.z())) & class_bit(CellState::kOccupied))) {
          continue;
        }
        const Index3 lo = (c.array() - 1).max(0), hi = (c.array() + 1).min(d.array() - 1);
        for (int z = lo.z(); z <= hi.z(); ++z) {
          for (int y = lo.y(); y <= hi.y(); ++y) {
            for (int x = lo.x(); x <= hi.x(); ++x) near[block(x, y, z)] = 1;
          }
        }
      }
    }
  }
  return near;
}

std::vector<std::uint8_t> uniform_block_codes(const BlockCensus& census,
                                              const std::vector<std::uint8_t>& near) {
  std::vector<std::uint8_t> codes(near.size(), kMixedBlock);
  for (std::size_t b = 0; b < codes.size(); ++b) {
    const std::uint8_t classes = census.classes(b);
    if (classes == class_bit(CellState::kFree)) {
      codes[b] = kFreeBlockCode;
    } else if (far_unobserved_block(classes, near[b] != 0)) {
      codes[b] = kFarCode;
    }
  }
  return codes;
}

}  // namespace vantage::detail
