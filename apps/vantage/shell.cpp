#include "shell.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <stdexcept>

#include "vantage/sim/scene.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage::cli {
namespace {

std::string shell_quote(const std::string& arg) {
  std::string quoted = "'";
  for (const char c : arg) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

std::vector<double> parse_numbers(std::string_view text, std::string_view what) {
  std::vector<double> numbers;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string item(text.substr(start, end - start));
    char* stop = nullptr;
    errno = 0;
    const double value = std::strtod(item.c_str(), &stop);
    if (item.empty() || stop != item.c_str() + item.size() || errno == ERANGE) {
      throw std::invalid_argument(
          fmt::format("{}: '{}' (item {}) is not a number", what, item, numbers.size()));
    }
    numbers.push_back(value);
    start = end + 1;
  }
  return numbers;
}

Eigen::Isometry3d parse_pose(std::string_view text, std::string_view what) {
  const std::vector<double> v = parse_numbers(text, what);
  if (v.size() != 6) {
    throw std::invalid_argument(
        fmt::format("{} needs 6 numbers x,y,z,roll,pitch,yaw (m, deg), got {}", what, v.size()));
  }
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) {
      throw std::invalid_argument(fmt::format("{}: item {} is {}", what, i, v[i]));
    }
  }
  return sim::pose_from_xyz_rpy({v[0], v[1], v[2]}, {deg2rad(v[3]), deg2rad(v[4]), deg2rad(v[5])});
}

Eigen::Vector3d roll_pitch_yaw(const Eigen::Matrix3d& R) {
  return {std::atan2(R(2, 1), R(2, 2)), -std::asin(std::clamp(R(2, 0), -1.0, 1.0)),
          std::atan2(R(1, 0), R(0, 0))};
}

std::string describe_pose(const Eigen::Isometry3d& T) {
  const Eigen::Vector3d t = T.translation();
  const Eigen::Vector3d rpy = roll_pitch_yaw(T.linear()) * (180.0 / std::numbers::pi);
  return fmt::format("x {:.4f} y {:.4f} z {:.4f} m, roll {:.3f} pitch {:.3f} yaw {:.3f} deg", t.x(),
                     t.y(), t.z(), rpy.x(), rpy.y(), rpy.z());
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
  std::string command = "/usr/bin/python3 " + shell_quote(path.string());
  for (const std::string& arg : args) command += " " + shell_quote(arg);
  if (std::system(command.c_str()) != 0) {
    throw std::runtime_error(fmt::format("plot script {} failed", path.filename().string()));
  }
}

}  // namespace vantage::cli
