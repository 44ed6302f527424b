#pragma once
/// @file
/// Choosing the next view from predicted gains (eq. 1).

#include <cstddef>
#include <cstdint>
#include <span>

namespace vantage {

/// Index of the highest gain; ties go to the lower index. Throws std::invalid_argument when
/// `gains` is empty or holds a NaN.
std::size_t choose_best(std::span<const double> gains);

/// Index of the highest score; among scores tied with it, the highest `tie_break` (Yamauchi's
/// nearest candidate: of views at the same place, the one that sees the most); then the lower
/// index. Throws std::invalid_argument when the spans are empty, differ in size or hold a NaN.
std::size_t choose_best(std::span<const double> scores, std::span<const double> tie_break);

/// A uniformly random index in [0, n), the same for the same seed on every platform. Throws
/// std::invalid_argument when n is 0.
std::size_t choose_random(std::size_t n, std::uint64_t seed);

}  // namespace vantage
