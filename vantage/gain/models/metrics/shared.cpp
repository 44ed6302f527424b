#include "vantage/gain/models/metrics/shared.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "vantage/util/parallel.hpp"

namespace vantage {

double area_factor(double x, double alpha) {
  if (x <= alpha) {
    const double a2 = alpha * alpha;
    return (-2.0 / (a2 * alpha)) * x * x * x + (3.0 / a2) * x * x;
  }
  const double m = alpha - 1.0, m3 = m * m * m;
  return (-2.0 * x * x * x + 3.0 * (alpha + 1.0) * x * x - 6.0 * alpha * x + 3.0 * alpha - 1.0) /
         m3;
}

std::vector<float> occupied_distance(const GainMap& map, double radius, int num_threads) {
  const GridSpec& spec = map.spec();
  std::vector<float> near(map.size(), std::numeric_limits<float>::infinity());
  const int r = static_cast<int>(std::floor(radius));
  struct Offset {
    Index3 d;
    std::ptrdiff_t linear;
    float distance;
  };
  const std::ptrdiff_t sy = spec.dims.x(), sz = sy * spec.dims.y();
  // The ball's offsets by ascending z; those of z = dz from first[dz + r] to first[dz + r + 1].
  std::vector<Offset> ball;
  std::vector<std::size_t> first;
  for (int z = -r; z <= r; ++z) {
    first.push_back(ball.size());
    for (int y = -r; y <= r; ++y) {
      for (int x = -r; x <= r; ++x) {
        const double d = std::sqrt(static_cast<double>(x * x + y * y + z * z));
        if (d <= radius)
          ball.push_back({Index3(x, y, z), x + sy * y + sz * z, static_cast<float>(d)});
      }
    }
  }
  first.push_back(ball.size());
  // NOTE: each occupied cell stamps the ball of `radius` around it; the minimum does not depend
  // on the order. Slabs of slices in parallel: each first lists its occupied cells, then writes
  // its own slices from the occupied cells within r slices of it, each stamping only the part of
  // its ball in the slab: the same for any thread count.
  constexpr int kSlab = 8;
  const int slabs = (spec.dims.z() + kSlab - 1) / kSlab;
  std::vector<std::vector<std::uint32_t>> occupied(static_cast<std::size_t>(slabs));
  run_with_threads(num_threads, [&] {
    tbb::parallel_for(0, slabs, [&](int slab) {
      const std::size_t from =
          static_cast<std::size_t>(slab * kSlab) * static_cast<std::size_t>(sz);
      const std::size_t to = std::min(map.size(), from + kSlab * static_cast<std::size_t>(sz));
      std::vector<std::uint32_t>& mine = occupied[static_cast<std::size_t>(slab)];
      for (std::size_t i = from; i < to; ++i) {
        if (map.value(i).state == CellState::kOccupied)
          mine.push_back(static_cast<std::uint32_t>(i));
      }
    });
    tbb::parallel_for(0, slabs, [&](int slab) {
      const int z0 = slab * kSlab, z1 = std::min(spec.dims.z(), z0 + kSlab);
      const int reach = (r + kSlab - 1) / kSlab;
      for (int other = std::max(0, slab - reach); other <= std::min(slabs - 1, slab + reach);
           ++other) {
        for (const std::uint32_t i : occupied[static_cast<std::size_t>(other)]) {
          const Index3 c = spec.unravel(i);
          const int dz_lo = std::max(-r, z0 - c.z()), dz_hi = std::min(r, z1 - 1 - c.z());
          if (dz_lo > dz_hi) continue;
          const bool inside = (c.array() >= r).all() && (c.array() < spec.dims.array() - r).all();
          const std::size_t k_end = first[static_cast<std::size_t>(dz_hi + r + 1)];
          for (std::size_t k = first[static_cast<std::size_t>(dz_lo + r)]; k < k_end; ++k) {
            const Offset& o = ball[k];
            if (!inside && !spec.contains(Index3(c + o.d))) continue;
            float& slot = near[static_cast<std::size_t>(static_cast<std::ptrdiff_t>(i) + o.linear)];
            slot = std::min(slot, o.distance);
          }
        }
      }
    });
  });
  return near;
}

}  // namespace vantage
