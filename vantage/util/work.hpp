#pragma once
/// @file
/// The work budget (issue 39): what a decision will cost in time and memory, estimated before it
/// runs and refused when it exceeds what the user allowed (docs/robustness.md, "Work").

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>

namespace vantage {

/// Wall time of one ray-cell step of a decision (a ray of the exact evaluation entering a cell
/// on its way to an unobserved one) on this project's 2-core test machine, shared, at two
/// threads [ns]: the slowest measured, the greedy reference of `vantage plan` over the 355
/// hemisphere views of examples/own-scans (walks across free space to the unobserved cells behind
/// the objects), took 6.4 ns a step under the load of three other sessions on the walker before
/// the one grid walker, 3.3 ns since (docs/robustness.md, "Work"; scripts/calibrate-work.sh for
/// the unobserved grid); 10 holds a margin of 50 % over the first, of 3 over the second.
inline constexpr double kNanosecondsPerStep = 10.0;

/// Wall time of one simulated ray of the surface yardstick's set-up (compute_surface_truth:
/// Embree's hit, and the scan's points to the surface cells they cover) on the same machine [ns]:
/// at most 79 ns measured (docs/robustness.md, "The yardstick's set-up").
inline constexpr double kNanosecondsPerSimulatedRay = 100.0;

/// The default of --max-work and of Python's set_budget(max_work=) [s of estimated work].
inline constexpr double kDefaultMaxWorkSeconds = 60.0;

/// Estimated seconds of `steps` ray-cell steps [s].
inline double work_seconds(double steps) { return steps * kNanosecondsPerStep * 1e-9; }

/// A number to `digits` significant digits, as printf's %g writes it ("1.4e+11", "86.2").
inline std::string significant(double value, int digits = 3) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

/// "0.5 s", "86.2 s", "14.1 min", "3.2 h": a duration in the unit that reads best.
inline std::string describe_seconds(double seconds) {
  if (seconds < 600.0) return significant(seconds) + " s";
  if (seconds < 3 * 3600.0) return significant(seconds / 60.0) + " min";
  return significant(seconds / 3600.0) + " h";
}

/// What a user allows a decision: its estimated work and memory, and the names the user set them
/// by (the CLI's options, Python's keywords), which a refusal names.
struct WorkBudget {
  double max_seconds = kDefaultMaxWorkSeconds;  ///< estimated work a decision may take [s]
  std::uint64_t max_bytes = 0;                  ///< [bytes]; 0: what the machine has available
  std::string_view work_option = "--max-work";
  std::string_view memory_option = "--max-memory";
};

/// A decision its budget does not allow: the command line's to change (the CLI's exit 2,
/// Python's ValueError), refused before any of it is computed.
struct WorkBudgetError : std::invalid_argument {
  WorkBudgetError(const std::string& message, bool past_memory)
      : std::invalid_argument(message), memory(past_memory) {}
  bool memory = false;  ///< refused for its memory, not its time
};

}  // namespace vantage
