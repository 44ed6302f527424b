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

/// A uniformly random index in [0, n), the same for the same seed on every platform. Throws
/// std::invalid_argument when n is 0.
std::size_t choose_random(std::size_t n, std::uint64_t seed);

}  // namespace vantage
