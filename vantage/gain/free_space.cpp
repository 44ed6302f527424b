#include "vantage/gain/free_space.hpp"

#include <algorithm>

namespace vantage {

FreeSpace free_space(const BlockCensus& census) {
  static_assert(FreeSpace::kShift == BlockCensus::kShift);
  FreeSpace free;
  free.dims = census.dims();
  const Index3 d = free.dims;
  const auto n = static_cast<std::size_t>(d.prod());
  const std::ptrdiff_t sx = 1, sy = d.x(), sz = static_cast<std::ptrdiff_t>(d.x()) * d.y();
  std::vector<std::uint8_t> all_free(n);
  for (std::size_t b = 0; b < n; ++b)
    all_free[b] = census.classes(b) == class_bit(CellState::kFree);
  // NOTE: the largest cube with a corner at each block, as the largest square of ones: one more
  // than the least of the seven neighbours ahead (blocks past the grid do not limit it), each
  // octant in one raster pass from its far corner.
  for (int o = 0; o < 8; ++o) {
    std::vector<std::uint8_t>& e = free.extent[static_cast<std::size_t>(o)];
    e.assign(n, 0);
    const int step[3] = {(o & 1) ? 1 : -1, (o & 2) ? 1 : -1, (o & 4) ? 1 : -1};
    const std::ptrdiff_t stride[3] = {step[0] * sx, step[1] * sy, step[2] * sz};
    for (int kz = 0; kz < d.z(); ++kz) {
      const int z = step[2] > 0 ? d.z() - 1 - kz : kz;
      const bool z_in = z + step[2] >= 0 && z + step[2] < d.z();
      for (int ky = 0; ky < d.y(); ++ky) {
        const int y = step[1] > 0 ? d.y() - 1 - ky : ky;
        const bool y_in = y + step[1] >= 0 && y + step[1] < d.y();
        for (int kx = 0; kx < d.x(); ++kx) {
          const int x = step[0] > 0 ? d.x() - 1 - kx : kx;
          const std::ptrdiff_t b = x + sy * y + sz * z;
          if (!all_free[static_cast<std::size_t>(b)]) continue;
          const bool x_in = x + step[0] >= 0 && x + step[0] < d.x();
          int least = 254;
          for (int m = 1; m < 8; ++m) {
            const bool mx = m & 1, my = m & 2, mz = m & 4;
            if ((mx && !x_in) || (my && !y_in) || (mz && !z_in)) continue;
            const std::ptrdiff_t nb =
                b + (mx ? stride[0] : 0) + (my ? stride[1] : 0) + (mz ? stride[2] : 0);
            least = std::min<int>(least, e[static_cast<std::size_t>(nb)]);
          }
          e[static_cast<std::size_t>(b)] = static_cast<std::uint8_t>(least + 1);
        }
      }
    }
  }
  return free;
}

}  // namespace vantage
