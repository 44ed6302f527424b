#pragma once
/// @file
/// What every subcommand of the CLI shares: parsing helpers, option checks, plots, and the error
/// convention (exceptions become one line on stderr and the exit code of docs/robustness.md, in
/// main).

#include <CLI/CLI.hpp>
#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace vantage::cli {

/// Exit codes (docs/robustness.md): done; the input or the run failed (a file that cannot be read
/// or is malformed, a setting in a file out of range, too little memory, a failed write or
/// picture); the command line is wrong (an unknown command or option, a missing, malformed or
/// out-of-range value, conflicting options), which is decided before any file is read.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

/// A wrong command line (exit code kExitUsage).
struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/// Runs `f`, which turns options into settings (their validate() throws std::invalid_argument
/// naming the field); its std::invalid_argument becomes a UsageError.
template <typename F>
auto from_options(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const UsageError&) {
    throw;
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

/// Prints `vantage: error: <message>` on stderr, non-printable bytes escaped and cut to one line
/// of at most 500 bytes; returns `code`.
int report_error(std::string_view message, int code);

/// Prints `vantage: warning: <message>` on stderr.
void warn(std::string_view message);

/// An option's value must be a finite number in [lo, hi], or (lo, hi] with `open_low`, [lo, hi)
/// with `open_high`: refused by CLI11 at parse time (exit code kExitUsage) with the option named.
CLI::Validator number_in(double lo, double hi, bool open_low = false, bool open_high = false);

/// An option's value must be a whole number in [lo, hi].
CLI::Validator whole_in(std::int64_t lo, std::int64_t hi);

/// A size of memory: bytes, or a number with K, M, G or T (powers of 1024), turned into bytes.
CLI::Validator memory_size();

/// A seed: a whole number in [0, 2^64 - 1], refused rather than wrapped or clamped.
CLI::Validator seed_value();

/// Refuses an output file that cannot be made: `path` is a directory, or its folder is missing or
/// not a folder (no output creates folders), or it is one of the run's `inputs` (the same file
/// by any path). Throws std::runtime_error naming `option` and the path.
void check_output_file(const std::filesystem::path& path, std::string_view option,
                       const std::vector<std::filesystem::path>& inputs = {});

/// Refuses a picture whose extension is none of the formats the plot scripts write (matplotlib's:
/// png, pdf, svg, jpg, ...), as a usage error (exit 2) before any work; the script would fail only
/// after it, or add ".png" to a name without an extension.
void check_picture_format(const std::filesystem::path& path, std::string_view option);

/// A file in the system's temporary folder, removed when this goes out of scope: the data a plot
/// script reads, never left beside the picture.
class TemporaryFile {
 public:
  explicit TemporaryFile(std::string_view suffix);
  ~TemporaryFile();
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// Parses "a,b,c" (an option's value) into numbers; throws UsageError naming `what` and the bad
/// item.
std::vector<double> parse_numbers(std::string_view text, std::string_view what);

/// Parses "x,y,z,roll,pitch,yaw" (m, degrees; rotations about the fixed x, y, z axes in that
/// order) into a pose; throws UsageError naming `what` when it is not six finite numbers.
Eigen::Isometry3d parse_pose(std::string_view text, std::string_view what);

/// Roll, pitch and yaw of a rotation, the inverse of parse_pose's angles [rad].
Eigen::Vector3d roll_pitch_yaw(const Eigen::Matrix3d& R);

/// `value`, or 0 when it prints as zero at `decimals` places: no "-0.0" for a value a hair
/// below zero (a yaw of -1e-15 deg).
double unsigned_zero(double value, int decimals);

/// "x 1.0000 y 0.0000 z 1.1000 m, roll 0.000 pitch 0.000 yaw 90.000 deg".
std::string describe_pose(const Eigen::Isometry3d& T);

/// The plot scripts' folder: VANTAGE_SCRIPTS_DIR from the environment, else an installed
/// binary's share/vantage/scripts, else the source tree's scripts/.
std::filesystem::path scripts_dir();

/// Runs `/usr/bin/python3 <scripts_dir()>/<script> args...`; when it fails, throws
/// std::runtime_error with the script's last line of error (not its traceback).
void run_plot_script(std::string_view script, const std::vector<std::string>& args);

}  // namespace vantage::cli
