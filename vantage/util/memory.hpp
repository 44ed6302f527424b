#pragma once
/// @file
/// The memory budget: what a grid-holding run will take, checked against what the machine has
/// free before anything is allocated.

#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include "vantage/util/text.hpp"

namespace vantage {

/// Bytes a new allocation can have now: /proc/meminfo's MemAvailable, or 0 when it cannot be read
/// (not Linux).
inline std::uint64_t available_memory() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  std::string unit;
  while (in >> key >> kib >> unit) {
    if (key == "MemAvailable:") return kib * 1024;
  }
  return 0;
}

/// What a run will hold: cells × bytes a cell (measured per run kind, docs/robustness.md), plus
/// a fixed part (scene, sensor, code) [bytes].
struct MemoryEstimate {
  std::uint64_t cells = 0;
  double bytes_per_cell = 0.0;
  double fixed_bytes = 0.0;
  std::uint64_t copies = 1;  ///< runs held at once (bench --jobs)

  double bytes() const {
    return static_cast<double>(copies) *
           (static_cast<double>(cells) * bytes_per_cell + fixed_bytes);
  }
};

/// "1.50 GiB", "340 MiB".
inline std::string describe_bytes(double bytes) {
  constexpr double kMiB = 1024.0 * 1024.0, kGiB = 1024.0 * kMiB;
  return bytes >= kGiB
             ? cat(static_cast<double>(static_cast<long long>(bytes / kGiB * 100)) / 100, " GiB")
             : cat(static_cast<long long>(bytes / kMiB + 0.5), " MiB");
}

/// Throws std::runtime_error naming `what` when the estimate exceeds `limit` bytes, or, when
/// `limit` is 0, the memory available now (a limit of 0 with nothing known checks nothing).
inline void check_memory(const MemoryEstimate& estimate, std::uint64_t limit,
                         std::string_view what) {
  const bool given = limit > 0;
  const std::uint64_t budget = given ? limit : available_memory();
  if (budget == 0 || estimate.bytes() <= static_cast<double>(budget)) return;
  throw std::runtime_error(
      cat(what, " needs about ", describe_bytes(estimate.bytes()), " (", estimate.cells,
          " cells x ", estimate.bytes_per_cell, " bytes",
          estimate.copies > 1 ? cat(" x ", estimate.copies, " jobs") : std::string(),
          "), more than ", given ? "--max-memory " : "the ",
          describe_bytes(static_cast<double>(budget)), given ? "" : " this machine has available",
          "; use a coarser resolution or a smaller region"));
}

}  // namespace vantage
