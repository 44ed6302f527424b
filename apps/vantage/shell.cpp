#include "shell.hpp"

#include <fmt/core.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "vantage/io/format_parsing.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/sim/scene.hpp"
#include "vantage/util/text.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage::cli {
namespace {

std::string shell_quote(const std::string& arg) {
  std::string quoted = "'";
  for (const char c : arg) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

/// The CLI's one logger: stderr, `vantage: <level>: <message>`.
spdlog::logger& logger() {
  static const std::shared_ptr<spdlog::logger> instance = [] {
    auto l = spdlog::stderr_logger_st("vantage");
    l->set_pattern("vantage: %l: %v");
    return l;
  }();
  return *instance;
}

/// A message as one printable line of at most 500 bytes.
std::string one_line(std::string_view message) {
  std::string line(message);
  std::replace(line.begin(), line.end(), '\n', ' ');
  return printable(line, 500);
}

}  // namespace

int report_error(std::string_view message, int code) {
  logger().error(one_line(message));
  return code;
}

void warn(std::string_view message) { logger().warn(one_line(message)); }

CLI::Validator number_in(double lo, double hi, bool open_low, bool open_high) {
  const std::string range =
      fmt::format("{}{}, {}{}", open_low ? "(" : "[", lo, hi, open_high ? ")" : "]");
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        const std::optional<double> value = parse_number(text);
        if (!value || !std::isfinite(*value) || *value < lo || (open_low && *value == lo) ||
            *value > hi || (open_high && *value == hi)) {
          return fmt::format("must be a number in {}, got '{}'", range, printable(text, 40));
        }
        return {};
      },
      "NUMBER in " + range);
}

CLI::Validator whole_in(std::int64_t lo, std::int64_t hi) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        std::int64_t value = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (error != std::errc() || end != text.data() + text.size() || value < lo || value > hi) {
          return fmt::format("must be a whole number in [{}, {}], got '{}'", lo, hi,
                             printable(text, 40));
        }
        return {};
      },
      fmt::format("INT in [{}, {}]", lo, hi));
}

CLI::Validator memory_size() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::string_view digits = text;
        double scale = 1.0;
        if (!digits.empty()) {
          const std::string_view units = "KMGT";
          if (const auto u = units.find(static_cast<char>(std::toupper(digits.back())));
              u != std::string_view::npos) {
            scale = std::pow(1024.0, static_cast<double>(u + 1));
            digits.remove_suffix(1);
          }
        }
        const std::optional<double> value = parse_number(digits);
        const double bytes = value ? *value * scale : -1.0;
        if (!(bytes >= 0.0 && bytes <= 1e18)) {
          return fmt::format("must be a size such as 512M or 4G, got '{}'", printable(text, 40));
        }
        text = std::to_string(static_cast<std::uint64_t>(bytes));
        return {};
      },
      "SIZE");
}

CLI::Validator seed_value() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (!parse_count(text)) {
          return fmt::format("must be a whole number in [0, 2^64 - 1], got '{}'",
                             printable(text, 40));
        }
        return {};
      },
      "SEED in [0, 2^64 - 1]");
}

void check_output_file(const std::filesystem::path& path, std::string_view option,
                       const std::vector<std::filesystem::path>& inputs) {
  namespace fs = std::filesystem;
  std::error_code error;
  for (const fs::path& input : inputs) {
    std::error_code a, b;
    if (fs::exists(input, a) && fs::exists(path, b) && fs::equivalent(path, input, error)) {
      throw std::runtime_error(fmt::format("{} {} is an input of this run ({}): write elsewhere",
                                           option, path.string(), input.string()));
    }
  }
  if (fs::is_directory(path, error)) {
    throw std::runtime_error(
        fmt::format("{} {} is a directory, not a file", option, path.string()));
  }
  const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  if (!fs::is_directory(folder, error)) {
    throw std::runtime_error(
        fmt::format("{} {}: {} {}", option, path.string(), folder.string(),
                    fs::exists(folder, error) ? "is not a folder" : "does not exist"));
  }
}

void check_picture_format(const std::filesystem::path& path, std::string_view option) {
  static constexpr std::array<std::string_view, 14> kFormats = {
      ".png",  ".pdf",  ".svg", ".svgz", ".jpg", ".jpeg", ".tif",
      ".tiff", ".webp", ".eps", ".ps",   ".pgf", ".raw",  ".rgba"};
  const std::string extension = lower_extension(path);
  if (std::find(kFormats.begin(), kFormats.end(), extension) == kFormats.end()) {
    throw UsageError(fmt::format(
        "{} {}: '{}' is not a picture format (give .png, .pdf, .svg, .jpg or another of "
        "matplotlib's)",
        option, printable(path.string(), 200), printable(extension, 20)));
  }
}

TemporaryFile::TemporaryFile(std::string_view suffix) {
  std::string pattern =
      (std::filesystem::temp_directory_path() / fmt::format("vantage-XXXXXX{}", suffix)).string();
  const int fd = mkstemps(pattern.data(), static_cast<int>(suffix.size()));
  if (fd < 0) {
    throw std::runtime_error(fmt::format("cannot create a temporary file in {}",
                                         std::filesystem::temp_directory_path().string()));
  }
  close(fd);
  path_ = pattern;
}

TemporaryFile::~TemporaryFile() {
  std::error_code error;
  std::filesystem::remove(path_, error);
}

std::vector<double> parse_numbers(std::string_view text, std::string_view what) {
  std::vector<double> numbers;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string_view item = text.substr(start, end - start);
    // NOTE: the strict reader every number of a file goes through: no hexadecimal ("0x1p-3" is
    // no occupancy), no leading space, no overflow to infinity.
    const std::optional<double> value = parse_number(item);
    if (!value) {
      throw UsageError(fmt::format("{}: '{}' (item {}) is not a number", what, printable(item, 40),
                                   numbers.size()));
    }
    numbers.push_back(*value);
    start = end + 1;
  }
  return numbers;
}

Eigen::Isometry3d parse_pose(std::string_view text, std::string_view what) {
  const std::vector<double> v = parse_numbers(text, what);
  if (v.size() != 6) {
    throw UsageError(
        fmt::format("{} needs 6 numbers x,y,z,roll,pitch,yaw (m, deg), got {}", what, v.size()));
  }
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) {
      throw UsageError(fmt::format("{}: item {} is {}", what, i, v[i]));
    }
    if (i < 3 && std::abs(v[i]) > kMaxWorldCoordinate) {
      throw UsageError(fmt::format("{}: {} = {} m lies beyond {} m of the origin", what, "xyz"[i],
                                   v[i], kMaxWorldCoordinate));
    }
    if (i >= 3 && std::abs(v[i]) > sim::kMaxAngleDegrees) {
      throw UsageError(fmt::format("{}: {} = {} deg lies outside [-{}, {}]", what,
                                   std::array{"roll", "pitch", "yaw"}[i - 3], v[i],
                                   sim::kMaxAngleDegrees, sim::kMaxAngleDegrees));
    }
  }
  return sim::pose_from_xyz_rpy({v[0], v[1], v[2]}, {deg2rad(v[3]), deg2rad(v[4]), deg2rad(v[5])});
}

Eigen::Vector3d roll_pitch_yaw(const Eigen::Matrix3d& R) {
  return {std::atan2(R(2, 1), R(2, 2)), -std::asin(std::clamp(R(2, 0), -1.0, 1.0)),
          std::atan2(R(1, 0), R(0, 0))};
}

double unsigned_zero(double value, int decimals) {
  return std::abs(value) < 0.5 * std::pow(10.0, -decimals) ? 0.0 : value;
}

std::string describe_pose(const Eigen::Isometry3d& T) {
  const Eigen::Vector3d t = T.translation();
  const Eigen::Vector3d rpy = roll_pitch_yaw(T.linear()) * (180.0 / std::numbers::pi);
  return fmt::format("x {:.4f} y {:.4f} z {:.4f} m, roll {:.3f} pitch {:.3f} yaw {:.3f} deg",
                     unsigned_zero(t.x(), 4), unsigned_zero(t.y(), 4), unsigned_zero(t.z(), 4),
                     unsigned_zero(rpy.x(), 3), unsigned_zero(rpy.y(), 3),
                     unsigned_zero(rpy.z(), 3));
}

std::filesystem::path scripts_dir() {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv("VANTAGE_SCRIPTS_DIR"); env != nullptr) return env;
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    const fs::path installed = self.parent_path() / VANTAGE_INSTALLED_SCRIPTS_DIR;
    if (fs::is_directory(installed, error)) return installed.lexically_normal();
  }
  return VANTAGE_SCRIPTS_DIR;
}

void run_plot_script(std::string_view script, const std::vector<std::string>& args) {
  const std::filesystem::path path = scripts_dir() / script;
  if (!std::filesystem::exists(path)) {
    throw std::runtime_error(
        fmt::format("plot script {} not found (set VANTAGE_SCRIPTS_DIR)", path.string()));
  }
  // NOTE: Debian's interpreter, which has python3-matplotlib; the python3 on PATH may differ.
  // NOTE: the script's stderr goes to a file: a failure is one line (its last), not a traceback.
  const TemporaryFile errors(".txt");
  std::string command = "/usr/bin/python3 " + shell_quote(path.string());
  for (const std::string& arg : args) command += " " + shell_quote(arg);
  command += " 2>" + shell_quote(errors.path().string());
  if (std::system(command.c_str()) != 0) {
    std::ifstream in(errors.path());
    std::string line, last;
    while (std::getline(in, line)) {
      if (line.find_first_not_of(" \t") != std::string::npos) last = line;
    }
    throw std::runtime_error(fmt::format("plot script {} failed: {}", path.filename().string(),
                                         last.empty() ? "no message" : last));
  }
}

}  // namespace vantage::cli
