#include "vantage/gain/free_space.hpp"

#include <algorithm>

namespace vantage {

FreeSpace free_space(const BlockCensus& census) {
  static_assert(FreeSpace::kShift == BlockCensus::kShift);
  FreeSpace free;
  free.dims = census.dims();
  const Index3 d = free.dims;
  const auto at = [&](int x, int y, int z) {
    return static_cast<std::size_t>(x) +
           static_cast<std::size_t>(d.x()) *
               (static_cast<std::size_t>(y) + static_cast<std::size_t>(d.y()) * z);
  };
  free.radius.resize(static_cast<std::size_t>(d.prod()));
  for (std::size_t b = 0; b < free.radius.size(); ++b) {
    free.radius[b] = census.classes(b) == class_bit(CellState::kFree) ? 255 : 0;
  }
  // The Chebyshev distance transform, two raster passes over the 26 neighbours: a free block's
  // radius is one more than the least of its neighbours' (blocks past the grid do not limit it).
  const auto pass = [&](int sign) {
    const auto range = [&](int a, auto&& body) {
      if (sign > 0) {
        for (int i = 0; i < d[a]; ++i) body(i);
      } else {
        for (int i = d[a] - 1; i >= 0; --i) body(i);
      }
    };
    range(2, [&](int z) {
      range(1, [&](int y) {
        range(0, [&](int x) {
          std::uint8_t& r = free.radius[at(x, y, z)];
          if (r == 0) return;
          int least = 254;
          // The 13 neighbours a raster pass in this direction has already visited.
          for (int dz = -1; dz <= 0; ++dz) {
            for (int dy = -1; dy <= 1; ++dy) {
              for (int dx = -1; dx <= 1; ++dx) {
                if (dz == 0 && (dy > 0 || (dy == 0 && dx >= 0))) continue;
                const int nx = x + sign * dx, ny = y + sign * dy, nz = z + sign * dz;
                if (nx < 0 || ny < 0 || nz < 0 || nx >= d.x() || ny >= d.y() || nz >= d.z()) {
                  continue;
                }
                least = std::min<int>(least, free.radius[at(nx, ny, nz)]);
              }
            }
          }
          r = static_cast<std::uint8_t>(std::min<int>(r, least + 1));
        });
      });
    });
  };
  pass(1);
  pass(-1);
  return free;
}

}  // namespace vantage
