#pragma once
/// @file
/// Message building for the core, which depends on Eigen and TBB only (no fmt).

#include <sstream>
#include <string>

namespace vantage {

/// Concatenates the arguments as `operator<<` prints them, numbers to 10 significant digits.
template <typename... Args>
std::string cat(const Args&... args) {
  std::ostringstream out;
  out.precision(10);
  (out << ... << args);
  return out.str();
}

}  // namespace vantage
