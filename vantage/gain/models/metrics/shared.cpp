#include "vantage/gain/models/metrics/shared.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

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

namespace {

/// An offset of a ball's cell from its centre.
struct Offset {
  Index3 d;
  std::ptrdiff_t linear;
  float distance;
};

/// A ball's parts: per set of occupied face neighbours (bit 2a: the one at +1 on axis a, bit 2a
/// + 1: at -1), the ball's offsets o with o_a <= 0, resp. >= 0, by ascending z; those of z = dz
/// from first[dz + r] to first[dz + r + 1].
struct BallParts {
  static constexpr int kSides = 64;
  std::vector<std::vector<Offset>> ball{kSides};
  std::vector<std::vector<std::size_t>> first{kSides};
};

BallParts ball_parts(const GridSpec& spec, double radius, int r) {
  const std::ptrdiff_t sy = spec.dims.x(), sz = sy * spec.dims.y();
  BallParts parts;
  for (int sides = 0; sides < BallParts::kSides; ++sides) {
    auto& ball = parts.ball[static_cast<std::size_t>(sides)];
    auto& first = parts.first[static_cast<std::size_t>(sides)];
    for (int z = -r; z <= r; ++z) {
      first.push_back(ball.size());
      for (int y = -r; y <= r; ++y) {
        for (int x = -r; x <= r; ++x) {
          const Index3 o(x, y, z);
          bool kept = true;
          for (int a = 0; a < 3; ++a) {
            if (((sides >> (2 * a)) & 1) && o[a] > 0) kept = false;
            if (((sides >> (2 * a + 1)) & 1) && o[a] < 0) kept = false;
          }
          const double d = std::sqrt(static_cast<double>(x * x + y * y + z * z));
          if (kept && d <= radius) ball.push_back({o, x + sy * y + sz * z, static_cast<float>(d)});
        }
      }
    }
    first.push_back(ball.size());
  }
  return parts;
}

/// The occupied cells of the slices [z0, z1) of cells, in ascending linear index, each with its
/// occupied face neighbours (BallParts' bits: +x, -x, +y, -y, +z, -z); with a census, only in the
/// blocks it says hold one. Read by the snapshot's codes (with_classes), each run's cells by their
/// row.
void list_occupied(const GainMap& map, const BlockCensus* census, int z0, int z1,
                   std::vector<std::pair<std::uint32_t, std::uint8_t>>& mine) {
  const GridSpec& spec = map.spec();
  const auto sy = static_cast<std::size_t>(spec.dims.x());
  const std::size_t sz = sy * static_cast<std::size_t>(spec.dims.y());
  with_classes(map, [&](const auto& class_of) {
    const auto occupied = [&](std::size_t j) {
      return class_of(j) == class_bit(CellState::kOccupied);
    };
    for_block_runs(spec, z0, z1, [&](std::size_t block, std::size_t first, int n) {
      if (census != nullptr && !(census->classes(block) & class_bit(CellState::kOccupied))) return;
      Index3 c = spec.unravel(first);
      for (std::size_t i = first; i < first + static_cast<std::size_t>(n); ++i, ++c.x()) {
        if (!occupied(i)) continue;
        int sides = 0;
        if (c.x() + 1 < spec.dims.x() && occupied(i + 1)) sides |= 1 << 0;
        if (c.x() > 0 && occupied(i - 1)) sides |= 1 << 1;
        if (c.y() + 1 < spec.dims.y() && occupied(i + sy)) sides |= 1 << 2;
        if (c.y() > 0 && occupied(i - sy)) sides |= 1 << 3;
        if (c.z() + 1 < spec.dims.z() && occupied(i + sz)) sides |= 1 << 4;
        if (c.z() > 0 && occupied(i - sz)) sides |= 1 << 5;
        mine.emplace_back(static_cast<std::uint32_t>(i), static_cast<std::uint8_t>(sides));
      }
    });
  });
}

}  // namespace

std::vector<float> occupied_distance(const GainMap& map, double radius, int num_threads,
                                     const BlockCensus* census) {
  const GridSpec& spec = map.spec();
  std::vector<float> near(map.size(), std::numeric_limits<float>::infinity());
  const int r = static_cast<int>(std::floor(radius));
  // NOTE: a cell whose nearest occupied cell is c never lies on the side of an occupied face
  // neighbour of c (that neighbour would lie nearer), so c stamps only the part of its ball on
  // no such side (BallParts). A wall's cell stamps a line.
  const BallParts parts = ball_parts(spec, radius, r);
  // NOTE: each occupied cell stamps its part of the ball of `radius` around it; the minimum does
  // not depend on the order. Slabs of slices in parallel: each first lists its occupied cells
  // with their occupied face neighbours, then writes its own slices from the occupied cells
  // within r slices of it, each stamping only the part of its ball in the slab: the same for any
  // thread count.
  constexpr int kSlab = 8;
  const int slabs = (spec.dims.z() + kSlab - 1) / kSlab;
  std::vector<std::vector<std::pair<std::uint32_t, std::uint8_t>>> occupied(
      static_cast<std::size_t>(slabs));
  run_with_threads(num_threads, [&] {
    tbb::parallel_for(0, slabs, [&](int slab) {
      list_occupied(map, census, slab * kSlab, std::min(spec.dims.z(), (slab + 1) * kSlab),
                    occupied[static_cast<std::size_t>(slab)]);
    });
    tbb::parallel_for(0, slabs, [&](int slab) {
      const int z0 = slab * kSlab, z1 = std::min(spec.dims.z(), z0 + kSlab);
      const int reach = (r + kSlab - 1) / kSlab;
      for (int other = std::max(0, slab - reach); other <= std::min(slabs - 1, slab + reach);
           ++other) {
        for (const auto& [i, sides] : occupied[static_cast<std::size_t>(other)]) {
          const Index3 c = spec.unravel(i);
          const int dz_lo = std::max(-r, z0 - c.z()), dz_hi = std::min(r, z1 - 1 - c.z());
          if (dz_lo > dz_hi) continue;
          const bool inside = (c.array() >= r).all() && (c.array() < spec.dims.array() - r).all();
          const std::vector<Offset>& part = parts.ball[sides];
          const std::vector<std::size_t>& at = parts.first[sides];
          const std::size_t k_end = at[static_cast<std::size_t>(dz_hi + r + 1)];
          for (std::size_t k = at[static_cast<std::size_t>(dz_lo + r)]; k < k_end; ++k) {
            const Offset& o = part[k];
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
