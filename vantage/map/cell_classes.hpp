#pragma once
/// @file
/// Every cell's class in two bits (docs/decision.md, "The swept search", item 6), kept by
/// OccupancyGrid as its cells change class: what the rays of the survival reading and greedy read,
/// a sixteenth of the grid's memory, so that a decision needs no snapshot of the grid.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "vantage/map/cell_state.hpp"

namespace vantage {

/// Packed classes, four cells a byte.
class CellClasses {
 public:
  CellClasses() = default;
  /// `cells` cells, all unobserved.
  explicit CellClasses(std::size_t cells) : bits_((cells + 3) / 4, 0) {}

  CellState operator[](std::size_t i) const {
    return static_cast<CellState>((bits_[i >> 2] >> ((i & 3u) * 2)) & 3u);
  }
  /// Cell `i` is now of class `state` (not thread-safe).
  void set(std::size_t i, CellState state) {
    std::uint8_t& b = bits_[i >> 2];
    const unsigned shift = static_cast<unsigned>(i & 3u) * 2;
    b = static_cast<std::uint8_t>((b & ~(3u << shift)) | (static_cast<unsigned>(state) << shift));
  }
  /// Every cell unobserved again.
  void reset() { std::fill(bits_.begin(), bits_.end(), std::uint8_t{0}); }
  /// Bytes it holds.
  std::size_t bytes() const { return bits_.size(); }
  /// The packed classes: cell i in bits 2 (i % 4) and up of byte i / 4.
  const std::uint8_t* packed() const { return bits_.data(); }

 private:
  static_assert(static_cast<int>(CellState::kUnobserved) == 0);
  std::vector<std::uint8_t> bits_;
};

}  // namespace vantage
