#pragma once
/// @file
/// A byte a cell for the walks of a metric raced cell by cell (metric_cells.hpp; docs/decision.md,
/// "A metric raced cell by cell"): each cell's state or, unobserved within D of an occupied cell,
/// its squared distance to the nearest one, where the snapshot's codes and the distances take five
/// bytes a cell.

#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "vantage/gain/free_space.hpp"
#include "vantage/gain/models/metrics/shared.hpp"
#include "vantage/gain/snapshot.hpp"
#include "vantage/map/block_census.hpp"
#include "vantage/util/parallel.hpp"

namespace vantage::detail {

/// What a listed cell's walks read of a cell (reach_codes), a byte a cell where the snapshot's
/// codes and the distances take five: an unobserved cell within D of an occupied one is coded by
/// its squared distance to the nearest occupied cell's centre, 0-16 [cells^2]; the others by
/// their class.
inline constexpr std::uint8_t kFarCode = 17;        ///< unobserved, beyond D of every occupied cell
inline constexpr std::uint8_t kFreeCode = 18;       ///< free, in a block of 4^3 cells not all free
inline constexpr std::uint8_t kFreeBlockCode = 19;  ///< free, in a block of free cells only
inline constexpr std::uint8_t kOccupiedCode = 20;

/// The distance [cells] of a code below kFarCode, as occupied_distance gives it, bit for bit.
inline const std::array<float, kFarCode> kCodeDistance = [] {
  std::array<float, kFarCode> out{};
  for (std::size_t n = 0; n < out.size(); ++n) {
    out[n] = static_cast<float>(std::sqrt(static_cast<double>(n)));
  }
  return out;
}();

/// The state a code stands for.
inline CellState code_state(std::uint8_t code) {
  return code < kFreeCode ? CellState::kUnobserved
                          : (code < kOccupiedCode ? CellState::kFree : CellState::kOccupied);
}

/// A block of reach_codes' `block_codes` whose cells do not all take one code.
inline constexpr std::uint8_t kMixedBlock = 0xFF;

/// Whether a block whose cells are of `classes` (class_bit()s) holds only unobserved cells beyond
/// D of every occupied one, given whether it is `near` an occupied cell's block
/// (near_occupied_blocks).
inline bool far_unobserved_block(std::uint8_t classes, bool near) {
  return classes == class_bit(CellState::kUnobserved) && !near;
}

/// Per block of `census`, whether it or one of its 26 neighbours holds an occupied cell. A
/// cell two blocks off on an axis lies at least 2 * 4 - 3 = 5 > D cells away, so every cell
/// within D of an occupied cell lies in such a block: a pass over the blocks (1/64 of the cells)
/// tells where to look.
std::vector<std::uint8_t> near_occupied_blocks(const BlockCensus& census);

/// Per block of the census, the code every cell of it takes in reach_codes when the census
/// tells it without a look at the cells: a block of free cells only (which lies in a free cube of
/// every octant), or of unobserved cells only, not near an occupied one (`near`,
/// near_occupied_blocks: beyond D of every occupied cell); else kMixedBlock.
std::vector<std::uint8_t> uniform_block_codes(const BlockCensus& census,
                                              const std::vector<std::uint8_t>& near);

/// Every cell's code (kFarCode's note) from the snapshot, the distances (occupied_distance,
/// within D) and the free space's blocks, on `num_threads` threads; the same for any number.
/// `block_codes`, empty or one per block of FreeSpace::kBlock cells a side (FreeSpace's blocks):
/// the code every cell of the block takes, read from the census without a look at its cells (a
/// block of free cells only, or of unobserved cells beyond D of every occupied one), or
/// kMixedBlock; the codes are the same with it as without.
inline std::vector<std::uint8_t> reach_codes(const GainMap& map, std::span<const float> near,
                                             const FreeSpace& free, int num_threads,
                                             std::span<const std::uint8_t> block_codes = {}) {
  static_assert(BlockCensus::kBlock == FreeSpace::kBlock);
  const GridSpec& spec = map.spec();
  std::vector<std::uint8_t> out(map.size());
  with_classes(map, [&](const auto& class_of) {
    run_with_threads(num_threads, [&] {
      tbb::parallel_for(0, spec.dims.z(), [&](int z) {
        for_block_runs(spec, z, z + 1, [&](std::size_t block, std::size_t first, int n) {
          const std::uint8_t whole = block_codes.empty() ? kMixedBlock : block_codes[block];
          if (whole != kMixedBlock) {
            std::fill_n(out.begin() + static_cast<std::ptrdiff_t>(first), n, whole);
            return;
          }
          // NOTE: a block of free cells only lies in a free cube of every octant.
          const std::uint8_t free_code =
              !free.empty() && free.extent[0][block] > 0 ? kFreeBlockCode : kFreeCode;
          for (std::size_t i = first; i < first + static_cast<std::size_t>(n); ++i) {
            const std::uint8_t bit = class_of(i);
            if (bit == class_bit(CellState::kFree)) {
              out[i] = free_code;
            } else if (bit == class_bit(CellState::kOccupied)) {
              out[i] = kOccupiedCode;
            } else if (!(near[i] <= kProximityCells)) {
              out[i] = kFarCode;
            } else {
              const double d = near[i];
              out[i] = static_cast<std::uint8_t>(std::lround(d * d));
            }
          }
        });
      });
    });
  });
  return out;
}

}  // namespace vantage::detail
