#pragma once
/// @file
/// Counter-based random numbers: the k-th draw of a stream depends on (seed, stream, k) only, so
/// a scan is the same whatever thread casts which ray.

#include <cmath>
#include <cstdint>
#include <numbers>

#include "vantage/util/hash.hpp"

namespace vantage::sim {

/// Independent random streams drawn from one seed.
enum class RandomStream : std::uint64_t { kPose = 1, kRange = 2, kPile = 3 };

/// Uniform in (0, 1), never 0 or 1: the k-th draw of `stream` for `seed`.
inline double uniform_open01(std::uint64_t seed, RandomStream stream, std::uint64_t k) {
  const std::uint64_t bits = mix64(mix64(seed ^ mix64(static_cast<std::uint64_t>(stream))) +
                                   mix64(k + 0x5851F42D4C957F2Dull));
  return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53;
}

/// Standard normal: the k-th draw of `stream` for `seed` (Box–Muller on draws 2k and 2k + 1).
inline double standard_normal(std::uint64_t seed, RandomStream stream, std::uint64_t k) {
  const double u1 = uniform_open01(seed, stream, 2 * k);
  const double u2 = uniform_open01(seed, stream, 2 * k + 1);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

}  // namespace vantage::sim
