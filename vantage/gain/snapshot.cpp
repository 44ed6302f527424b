#include "vantage/gain/snapshot.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>

#include "vantage/gain/ray_model.hpp"
#include "vantage/util/parallel.hpp"

namespace vantage {
namespace {

constexpr std::size_t kSnapshotChunk = std::size_t{1} << 16;

/// A total order on floats that matches numeric order for every non-NaN value.
std::uint32_t ordered_key(float f) {
  const auto b = std::bit_cast<std::uint32_t>(f);
  return (b & 0x80000000u) ? ~b : (b | 0x80000000u);
}
float from_ordered_key(std::uint32_t k) {
  return std::bit_cast<float>((k & 0x80000000u) ? (k & 0x7fffffffu) : ~k);
}

template <typename Code>
void write_codes(std::span<const float> log_odds, std::span<const std::uint32_t> keys,
                 Code* codes) {
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, log_odds.size(), kSnapshotChunk), [&](const auto& r) {
        std::uint32_t last_key = ordered_key(log_odds[r.begin()]);
        auto last_code =
            static_cast<Code>(std::lower_bound(keys.begin(), keys.end(), last_key) - keys.begin());
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const std::uint32_t key = ordered_key(log_odds[i]);
          if (key != last_key) {
            last_key = key;
            last_code =
                static_cast<Code>(std::lower_bound(keys.begin(), keys.end(), key) - keys.begin());
          }
          codes[i] = last_code;
        }
      });
}

}  // namespace

GainMap::GainMap(const OccupancyGrid& grid, int num_threads)
    : spec_(grid.spec()), params_(grid.params()) {
  const std::span<const float> log_odds = grid.log_odds();
  const std::size_t n = log_odds.size();
  const std::size_t chunks = (n + kSnapshotChunk - 1) / kSnapshotChunk;
  std::vector<std::uint32_t> keys;
  run_with_threads(num_threads, [&] {
    // Distinct values per fixed chunk, then merged: the table does not depend on the threads.
    std::vector<std::vector<std::uint32_t>> distinct(chunks);
    tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
      std::vector<std::uint32_t>& out = distinct[c];
      const std::size_t end = std::min(n, (c + 1) * kSnapshotChunk);
      std::uint32_t last = ordered_key(log_odds[c * kSnapshotChunk]);
      out.push_back(last);
      for (std::size_t i = c * kSnapshotChunk; i < end; ++i) {
        const std::uint32_t key = ordered_key(log_odds[i]);
        if (key != last) out.push_back(last = key);
      }
      std::sort(out.begin(), out.end());
      out.erase(std::unique(out.begin(), out.end()), out.end());
    });
    for (const auto& part : distinct) keys.insert(keys.end(), part.begin(), part.end());
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());

    values_.reserve(keys.size());
    for (const std::uint32_t key : keys) {
      const float l = from_ordered_key(key);
      Value v;
      v.p = logistic(l);  // as OccupancyGrid::probability
      v.entropy = entropy_bits(v.p);
      v.state = grid.state_of(l);
      values_.push_back(v);
    }
    code_width_ = keys.size() <= 0x100u ? 1 : (keys.size() <= 0x10000u ? 2 : 4);
    switch (code_width_) {
      case 1:
        codes8_.resize(n);
        write_codes(log_odds, keys, codes8_.data());
        break;
      case 2:
        codes16_.resize(n);
        write_codes(log_odds, keys, codes16_.data());
        break;
      default:
        codes32_.resize(n);
        write_codes(log_odds, keys, codes32_.data());
        break;
    }
  });
}

namespace {

/// Each block's common code (or kMixed) and whether it holds an unobserved cell.
template <typename CodeT>
void block_codes(const GridSpec& spec, const CodeT* codes, std::span<const GainMap::Value> values,
                 BlockSummary& blocks) {
  constexpr int kBlock = BlockSummary::kBlock;
  const Index3& bd = blocks.dims;
  tbb::parallel_for(0, bd.z(), [&](int bz) {
    for (int by = 0; by < bd.y(); ++by) {
      for (int bx = 0; bx < bd.x(); ++bx) {
        const Index3 lo(bx * kBlock, by * kBlock, bz * kBlock);
        const Index3 hi = (lo.array() + kBlock).min(spec.dims.array());
        const std::size_t first = spec.linear(lo);
        const auto code = static_cast<std::uint32_t>(codes[first]);
        bool uniform = code < BlockSummary::kMixed;
        bool unobserved = false;
        for (int z = lo.z(); z < hi.z(); ++z) {
          for (int y = lo.y(); y < hi.y(); ++y) {
            const std::size_t row = spec.linear(Index3(lo.x(), y, z));
            for (int x = 0; x < hi.x() - lo.x(); ++x) {
              const auto c = codes[row + static_cast<std::size_t>(x)];
              uniform = uniform && c == codes[first];
              unobserved = unobserved || values[c].state == CellState::kUnobserved;
            }
          }
        }
        const std::size_t b = blocks.at(bx, by, bz);
        if (uniform) blocks.code[b] = static_cast<std::uint16_t>(code);
        blocks.unobserved[b] = unobserved ? 1 : 0;
      }
    }
  });
}

constexpr std::uint8_t kFar = 255;

/// 0 for the blocks on a border: mixed, or beside a block of another code or outside the grid
/// (rays come from there as free space); kFar elsewhere.
std::vector<std::uint8_t> borders(const BlockSummary& blocks) {
  const Index3& bd = blocks.dims;
  std::vector<std::uint8_t> dist(blocks.code.size(), kFar);
  for (int z = 0; z < bd.z(); ++z) {
    for (int y = 0; y < bd.y(); ++y) {
      for (int x = 0; x < bd.x(); ++x) {
        const std::uint16_t c = blocks.code[blocks.at(x, y, z)];
        bool border = c == BlockSummary::kMixed;
        for (int dz = -1; dz <= 1 && !border; ++dz) {
          for (int dy = -1; dy <= 1 && !border; ++dy) {
            for (int dx = -1; dx <= 1 && !border; ++dx) {
              const int nx = x + dx, ny = y + dy, nz = z + dz;
              border = nx < 0 || ny < 0 || nz < 0 || nx >= bd.x() || ny >= bd.y() || nz >= bd.z() ||
                       blocks.code[blocks.at(nx, ny, nz)] != c;
            }
          }
        }
        if (border) dist[blocks.at(x, y, z)] = 0;
      }
    }
  }
  return dist;
}

/// Turns `dist` into the chessboard distance to the nearest border block: two chamfer passes over
/// the 26 neighbours. All blocks within it share the block's code, because blocks off the border
/// share their neighbours' codes.
void chamfer(const Index3& bd, const BlockSummary& blocks, std::vector<std::uint8_t>& dist) {
  for (const int dir : {1, -1}) {
    const int z0 = dir > 0 ? 0 : bd.z() - 1, y0 = dir > 0 ? 0 : bd.y() - 1,
              x0 = dir > 0 ? 0 : bd.x() - 1;
    for (int z = z0; z >= 0 && z < bd.z(); z += dir) {
      for (int y = y0; y >= 0 && y < bd.y(); y += dir) {
        for (int x = x0; x >= 0 && x < bd.x(); x += dir) {
          std::uint8_t& d = dist[blocks.at(x, y, z)];
          for (int dz = -1; dz <= 1; ++dz) {
            for (int dy = -1; dy <= 1; ++dy) {
              for (int dx = -1; dx <= 1; ++dx) {
                // Only the neighbours this pass has already visited.
                const int order = dir * (dz * 9 + dy * 3 + dx);
                if (order >= 0) continue;
                const int nx = x + dx, ny = y + dy, nz = z + dz;
                if (nx < 0 || ny < 0 || nz < 0 || nx >= bd.x() || ny >= bd.y() || nz >= bd.z()) {
                  continue;
                }
                const std::uint8_t nd = dist[blocks.at(nx, ny, nz)];
                if (nd < kFar && nd + 1 < d) d = static_cast<std::uint8_t>(nd + 1);
              }
            }
          }
        }
      }
    }
  }
}

}  // namespace

BlockSummary summarize_blocks(const GainMap& map) {
  const GridSpec& spec = map.spec();
  BlockSummary blocks;
  blocks.dims = (spec.dims.array() + (BlockSummary::kBlock - 1)) / BlockSummary::kBlock;
  const Index3& bd = blocks.dims;
  const std::size_t n = static_cast<std::size_t>(bd.x()) * bd.y() * bd.z();
  blocks.code.assign(n, BlockSummary::kMixed);
  blocks.radius.assign(n, 0);
  blocks.unobserved.assign(n, 0);
  switch (map.code_width()) {
    case 1:
      block_codes(spec, map.codes<std::uint8_t>(), map.values(), blocks);
      break;
    case 2:
      block_codes(spec, map.codes<std::uint16_t>(), map.values(), blocks);
      break;
    default:
      block_codes(spec, map.codes<std::uint32_t>(), map.values(), blocks);
      break;
  }
  std::vector<std::uint8_t> dist = borders(blocks);
  chamfer(bd, blocks, dist);
  for (std::size_t i = 0; i < n; ++i) {
    blocks.radius[i] = blocks.code[i] == BlockSummary::kMixed ? 0 : dist[i];
  }
  return blocks;
}

}  // namespace vantage
