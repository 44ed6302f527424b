#include "shell.hpp"

#include <fmt/core.h>

#include <cerrno>
#include <cstdlib>
#include <stdexcept>

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

void run_plot_script(std::string_view script, const std::vector<std::string>& args) {
  const char* env = std::getenv("VANTAGE_SCRIPTS_DIR");
  const std::filesystem::path dir = env != nullptr ? env : VANTAGE_SCRIPTS_DIR;
  const std::filesystem::path path = dir / script;
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
