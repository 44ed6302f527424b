#include "vantage/gain/free_space.hpp"

#include <algorithm>

namespace vantage {

FreeSpace free_space(const BlockCensus& census) {
  static_assert(FreeSpace::kShift == BlockCensus::kShift);
  FreeSpace free;
  free.dims = census.dims();
  const Index3 d = free.dims;
  const auto n = static_cast<std::size_t>(d.prod());
  const std::ptrdiff_t sy = d.x(), sz = static_cast<std::ptrdiff_t>(d.x()) * d.y();
  std::vector<std::uint8_t> all_free(n);
  for (std::size_t b = 0; b < n; ++b)
    all_free[b] = census.classes(b) == class_bit(CellState::kFree);
  // NOTE: the largest cube with a corner at each block, as the largest square of ones: one more
  // than the least of the seven neighbours ahead (blocks past the grid do not limit it), each
  // octant in one raster pass from its far corner. Per row, the six neighbours in the rows
  // ahead first (a loop the compiler vectorises), then the one ahead in the row itself.
  const auto nx = static_cast<std::size_t>(d.x());
  std::vector<std::uint8_t> ahead(nx);
  for (int o = 0; o < 8; ++o) {
    std::vector<std::uint8_t>& e = free.extent[static_cast<std::size_t>(o)];
    e.assign(n, 0);
    const bool up_x = (o & 1) != 0;
    const int step_y = (o & 2) ? 1 : -1, step_z = (o & 4) ? 1 : -1;
    for (int kz = 0; kz < d.z(); ++kz) {
      const int z = step_z > 0 ? d.z() - 1 - kz : kz;
      const bool z_in = z + step_z >= 0 && z + step_z < d.z();
      for (int ky = 0; ky < d.y(); ++ky) {
        const int y = step_y > 0 ? d.y() - 1 - ky : ky;
        const bool y_in = y + step_y >= 0 && y + step_y < d.y();
        const std::ptrdiff_t row = sy * y + sz * z;
        std::fill(ahead.begin(), ahead.end(), std::uint8_t{254});
        const auto take = [&](std::ptrdiff_t other) {
          const std::uint8_t* r = e.data() + other;
          for (std::size_t x = 0; x < nx; ++x) ahead[x] = std::min(ahead[x], r[x]);
          if (up_x) {
            for (std::size_t x = 0; x + 1 < nx; ++x) ahead[x] = std::min(ahead[x], r[x + 1]);
          } else {
            for (std::size_t x = 1; x < nx; ++x) ahead[x] = std::min(ahead[x], r[x - 1]);
          }
        };
        if (y_in) take(row + step_y * sy);
        if (z_in) take(row + step_z * sz);
        if (y_in && z_in) take(row + step_y * sy + step_z * sz);
        std::uint8_t* out = e.data() + row;
        const std::uint8_t* is_free = all_free.data() + row;
        std::uint8_t next = 254;  // the block ahead in the row; none past the grid
        for (std::size_t k = 0; k < nx; ++k) {
          const std::size_t x = up_x ? nx - 1 - k : k;
          const std::uint8_t least = std::min(ahead[x], next);
          out[x] = is_free[x] ? static_cast<std::uint8_t>(least + 1) : std::uint8_t{0};
          next = out[x];
        }
      }
    }
  }
  return free;
}

}  // namespace vantage
