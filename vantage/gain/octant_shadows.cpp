#include "vantage/gain/octant_shadows.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>

#include "vantage/util/parallel.hpp"

namespace vantage {
namespace {

/// Per row (y, z) of cells along x, the occupied cells' bits in `words` words a row: bit x into
/// `up`, bit dims.x - 1 - x into `down`.
void occupied_rows(const GridSpec& spec, const CellClasses& classes, const BlockCensus& census,
                   std::size_t words, int num_threads, std::vector<std::uint64_t>& up,
                   std::vector<std::uint64_t>& down) {
  const int nx = spec.dims.x();
  const std::size_t rows = static_cast<std::size_t>(spec.dims.y()) * spec.dims.z();
  up.assign(rows * words, 0);
  down.assign(rows * words, 0);
  const std::uint8_t* packed = classes.packed();
  static_assert(static_cast<int>(CellState::kOccupied) == 2);
  run_with_threads(num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, rows, [&](std::size_t r) {
      std::uint64_t* row_up = up.data() + r * words;
      std::uint64_t* row_down = down.data() + r * words;
      const std::size_t first = r * static_cast<std::size_t>(nx);
      // NOTE: most rows cross blocks with no occupied cell only (the census says so).
      const Index3 cell(0, static_cast<int>(r % spec.dims.y()),
                        static_cast<int>(r / spec.dims.y()));
      const std::size_t block = census.block_of(cell);
      bool any = false;
      for (int b = 0; b < census.dims().x() && !any; ++b) {
        any = census.count(block + static_cast<std::size_t>(b), CellState::kOccupied) > 0;
      }
      if (!any) return;
      for (int x = 0; x < nx; ++x) {
        const std::size_t i = first + static_cast<std::size_t>(x);
        if (((packed[i >> 2] >> ((i & 3u) * 2)) & 3u) != 2u) continue;
        row_up[static_cast<std::size_t>(x >> 6)] |= std::uint64_t{1} << (x & 63);
        const int b = nx - 1 - x;
        row_down[static_cast<std::size_t>(b >> 6)] |= std::uint64_t{1} << (b & 63);
      }
    });
  });
}

}  // namespace

OctantShadows::OctantShadows(const GridSpec& spec, const CellClasses& classes,
                             const BlockCensus& census, int num_threads)
    : spec_(spec), words_((static_cast<std::size_t>(spec.dims.x()) + 63) / 64) {
  const int ny = spec.dims.y(), nz = spec.dims.z();
  const std::size_t rows = static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz);
  const std::size_t words = words_;
  std::vector<std::uint64_t> up, down;
  occupied_rows(spec, classes, census, words, num_threads, up, down);
  run_with_threads(num_threads, [&] {
    tbb::parallel_for(0, 8, [&](int octant) {
      const std::vector<std::uint64_t>& occupied = (octant & 1) ? up : down;
      std::vector<std::uint64_t>& ob = rows_[static_cast<std::size_t>(octant)];
      ob.assign(rows * words, 0);
      const int sy = (octant & 2) ? 1 : -1, sz = (octant & 4) ? 1 : -1;
      std::vector<std::uint64_t> c(words), s(words);
      for (int kz = 0; kz < nz; ++kz) {
        const int z = sz > 0 ? kz : nz - 1 - kz;
        for (int ky = 0; ky < ny; ++ky) {
          const int y = sy > 0 ? ky : ny - 1 - ky;
          const std::size_t row = static_cast<std::size_t>(y) + static_cast<std::size_t>(ny) * z;
          const std::uint64_t* o = occupied.data() + row * words;
          // NOTE: a row past the grid's face is open: no cell of this one has both of its
          // predecessors on y and z blocked.
          if (kz == 0 || ky == 0) {
            std::copy(o, o + words, ob.data() + row * words);
            continue;
          }
          const std::uint64_t* by = ob.data() + (row - static_cast<std::size_t>(sy)) * words;
          const std::uint64_t* bz =
              ob.data() +
              (row - static_cast<std::size_t>(sz) * static_cast<std::size_t>(ny)) * words;
          // C: both predecessors on y and z blocked; T: the predecessor on x occupied (bit 0's
          // lies past the face). Within each run of C, every cell from the first whose x
          // predecessor is occupied on is blocked: the seeds S = C & T filled up the run by an
          // addition, whose carry runs from each run's first seed to the run's end.
          std::uint64_t carry_in = 0;
          for (std::size_t w = 0; w < words; ++w) {
            c[w] = by[w] & bz[w];
            const std::uint64_t t = (o[w] << 1) | carry_in;
            carry_in = o[w] >> 63;
            s[w] = c[w] & t;
          }
          std::uint64_t carry = 0;
          std::uint64_t* out = ob.data() + row * words;
          for (std::size_t w = 0; w < words; ++w) {
            const std::uint64_t partial = c[w] + s[w];
            const std::uint64_t sum = partial + carry;
            carry = (partial < c[w] || sum < partial) ? 1 : 0;
            out[w] = o[w] | (c[w] & ~sum) | s[w];
          }
        }
      }
    });
  });
}

std::uint8_t OctantShadows::bits(const Index3& cell) const {
  std::uint8_t out = 0;
  for (int o = 0; o < 8; ++o) out |= static_cast<std::uint8_t>(bit(o, cell) << o);
  return out;
}

std::uint8_t OctantShadows::octants(const Eigen::Vector3d& origin, const Index3& lo,
                                    const Index3& hi) const {
  std::uint8_t out = 0xff;
  for (int a = 0; a < 3; ++a) {
    const double below = spec_.origin[a] + lo[a] * spec_.resolution;
    const double above = spec_.origin[a] + (hi[a] + 1) * spec_.resolution;
    // NOTE: a walk that does not move on an axis takes the lower step there (GridWalk): either
    // value then, as when the origin lies within the cells' slab.
    std::uint8_t keep = 0xff;
    if (origin[a] < below) {
      keep = 0;
      for (int o = 0; o < 8; ++o) keep |= static_cast<std::uint8_t>(((o >> a) & 1) << o);
    } else if (origin[a] > above) {
      keep = 0;
      for (int o = 0; o < 8; ++o) keep |= static_cast<std::uint8_t>((((o >> a) & 1) ^ 1) << o);
    }
    out &= keep;
  }
  return out;
}

std::uint8_t OctantShadows::open_octants(const Eigen::Vector3d& origin) const {
  const Index3 cell = spec_.lattice_index(origin);
  if (!spec_.contains(cell)) return 0xff;
  return static_cast<std::uint8_t>(~bits(cell));
}

std::vector<std::uint32_t> OctantShadows::reachable(std::span<const Eigen::Vector3d> origins,
                                                    std::span<const std::uint32_t> cells,
                                                    int num_threads) const {
  if (cells.empty()) return {};
  Index3 lo = spec_.dims, hi = Index3::Constant(-1);
  for (const std::uint32_t i : cells) {
    const Index3 c = spec_.unravel(i);
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  // NOTE: the octants any origin's walks to the cells' box may take, each of which must start
  // open; a cell is left out when it is shadowed in all of them.
  std::uint8_t used = 0;
  for (const Eigen::Vector3d& origin : origins) {
    const std::uint8_t need = octants(origin, lo, hi);
    if ((need & open_octants(origin)) != need) return {cells.begin(), cells.end()};
    used |= need;
  }
  // NOTE: in fixed runs of cells, joined in order: the same list for any thread count.
  constexpr std::size_t kRun = 4096;
  std::vector<std::vector<std::uint32_t>> runs((cells.size() + kRun - 1) / kRun);
  run_with_threads(num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, runs.size(), [&](std::size_t r) {
      for (std::size_t k = r * kRun; k < std::min(cells.size(), (r + 1) * kRun); ++k) {
        if ((bits(spec_.unravel(cells[k])) & used) != used) runs[r].push_back(cells[k]);
      }
    });
  });
  std::vector<std::uint32_t> out;
  out.reserve(cells.size());
  for (const std::vector<std::uint32_t>& run : runs) out.insert(out.end(), run.begin(), run.end());
  return out;
}

}  // namespace vantage
