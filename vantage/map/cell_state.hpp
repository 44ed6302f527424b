#pragma once
/// @file
/// The three classes of a cell (docs/model.md, "Cells and their states").

#include <cstdint>

namespace vantage {

/// The three classes of docs/model.md: unobserved 0.4 < p < 0.6, free p <= 0.4, occupied p >= 0.6.
enum class CellState : std::uint8_t { kUnobserved = 0, kFree = 1, kOccupied = 2 };

inline constexpr double kFreeMaxProbability = 0.4;      ///< p <= this is free
inline constexpr double kOccupiedMinProbability = 0.6;  ///< p >= this is occupied

/// Class of a probability by docs/model.md's thresholds.
inline CellState classify(double p) {
  if (p <= kFreeMaxProbability) return CellState::kFree;
  if (p >= kOccupiedMinProbability) return CellState::kOccupied;
  return CellState::kUnobserved;
}

/// A class's bit in a set of classes: unobserved 1, free 2, occupied 4.
constexpr std::uint8_t class_bit(CellState state) {
  return static_cast<std::uint8_t>(1u << static_cast<unsigned>(state));
}

}  // namespace vantage
