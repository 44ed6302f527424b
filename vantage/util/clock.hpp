#pragma once
/// @file
/// Wall time for the timings every stage records.

#include <chrono>

namespace vantage {

/// Seconds of wall time since `start` [s].
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace vantage
