#pragma once
/// @file
/// The memory budget: what a grid-holding run will take, checked against what the machine has
/// free before anything is allocated.

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "vantage/util/limits.hpp"
#include "vantage/util/text.hpp"

namespace vantage {

/// The first number of a file (a /proc or /sys entry), or nothing.
inline std::optional<std::uint64_t> first_number_in(const char* file) {
  std::ifstream in(file);
  std::uint64_t value = 0;
  if (in >> value) return value;
  return std::nullopt;
}

/// Bytes a new allocation can have now: the least of /proc/meminfo's MemAvailable, what this
/// process's limits leave (`ulimit -v` and `-d`: RLIMIT_AS and RLIMIT_DATA less what it uses) and
/// what its cgroup's memory.max leaves (a container's limit); 0 when none can be read (not
/// Linux).
inline std::uint64_t available_memory() {
  std::uint64_t available = 0;
  const auto bound = [&](std::uint64_t limit, std::uint64_t used) {
    // NOTE: 1, not 0, when nothing is left: 0 says "unknown" to check_memory.
    const std::uint64_t left = limit > used ? limit - used : 1;
    available = available == 0 ? left : std::min(available, left);
  };
  {
    std::ifstream in("/proc/meminfo");
    std::string key, unit;
    std::uint64_t kib = 0;
    while (in >> key >> kib >> unit) {
      if (key == "MemAvailable:") {
        available = kib * 1024;
        break;
      }
    }
  }
  // /proc/self/statm: total program size, resident, shared, text, lib, data + stack [pages].
  std::ifstream statm("/proc/self/statm");
  std::array<std::uint64_t, 6> pages{};
  for (std::uint64_t& p : pages) statm >> p;
  const auto page = static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    bound(limit.rlim_cur, pages[0] * page);
  }
  if (getrlimit(RLIMIT_DATA, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    bound(limit.rlim_cur, pages[5] * page);
  }
  // NOTE: memory.max reads "max" when unlimited, which is no number.
  const auto cgroup_max = first_number_in("/sys/fs/cgroup/memory.max");
  const auto cgroup_current = first_number_in("/sys/fs/cgroup/memory.current");
  if (cgroup_max && cgroup_current) bound(*cgroup_max, *cgroup_current);
  return available;
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

/// Bytes a cell of an OccupancyGrid holds: its log-odds (a float), its class (2 bits) and its
/// share of its block's census (3 bytes a 4^3 block).
inline constexpr double kOccupancyGridBytesPerCell = 4.0 + 0.25 + 3.0 / 64.0;

/// Bytes a grid cell costs mapping and planning at their peak (`vantage plan`, `explore`, a bench
/// trial; a Mapper and a plan in Python): measured 52.0 B a cell at the margin on `vantage plan
/// --map` of maps of 8 to 64 M cells, every cell known, at 1 and 2 threads (docs/robustness.md,
/// "Memory"), and earlier 4.4 B more a thread on `plan` of a manifest; so 50 + 5 a thread,
/// which is 55 at one thread and 60 at two.
inline constexpr double kMappingBytesPerCell = 50.0;
inline constexpr double kMappingThreadBytesPerCell = 5.0;

/// Bytes a cell costs mapping and planning on `threads` threads.
inline double mapping_bytes_per_cell(int threads) {
  return kMappingBytesPerCell + kMappingThreadBytesPerCell * std::max(1, threads);
}

/// "1.5 GiB", "340 MiB", "1 KiB", "512 bytes": never "0 MiB" for a size that is not 0, which
/// would read as no limit (issue 39: `--max-memory 1K`).
inline std::string describe_bytes(double bytes) {
  const auto kib = static_cast<double>(kKiB), mib = static_cast<double>(kMiB),
             gib = static_cast<double>(kGiB);
  if (bytes >= gib) {
    return cat(static_cast<double>(static_cast<long long>(bytes / gib * 100)) / 100, " GiB");
  }
  if (bytes >= mib) return cat(static_cast<long long>(bytes / mib + 0.5), " MiB");
  if (bytes >= kib) return cat(static_cast<long long>(bytes / kib + 0.5), " KiB");
  return cat(static_cast<long long>(bytes), " bytes");
}

/// The memory budget refused a run: a std::runtime_error (the CLI's exit 1; Python's
/// MemoryError).
struct MemoryBudgetError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Throws MemoryBudgetError naming `what` when the estimate exceeds `limit` bytes, or, when
/// `limit` is 0, the memory available now (a limit of 0 with nothing known checks nothing);
/// `option` is the limit's name where the user set it.
inline void check_memory(const MemoryEstimate& estimate, std::uint64_t limit, std::string_view what,
                         std::string_view option = "--max-memory") {
  const bool given = limit > 0;
  const std::uint64_t budget = given ? limit : available_memory();
  if (budget == 0 || estimate.bytes() <= static_cast<double>(budget)) return;
  throw MemoryBudgetError(
      cat(what, " needs about ", describe_bytes(estimate.bytes()), " (", estimate.cells,
          " cells x ", estimate.bytes_per_cell, " bytes",
          estimate.copies > 1 ? cat(" x ", estimate.copies, " jobs") : std::string(),
          "), more than ", given ? cat(option, " ") : std::string("the "),
          describe_bytes(static_cast<double>(budget)), given ? "" : " this machine has available",
          "; use a coarser resolution or a smaller region"));
}

}  // namespace vantage
