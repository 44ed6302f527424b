#pragma once
/// @file
/// Message building for the core, which depends on Eigen and TBB only (no fmt).

#include <array>
#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace vantage {

/// Concatenates the arguments as `operator<<` prints them, numbers to 10 significant digits.
template <typename... Args>
std::string cat(const Args&... args) {
  std::ostringstream out;
  out.precision(10);
  (out << ... << args);
  return out.str();
}

/// The names of an enum's values, for to_string and parse functions.
template <typename E, std::size_t N>
using EnumNames = std::array<std::pair<E, std::string_view>, N>;

/// The name of `value` in `names`, or "unknown".
template <typename E, std::size_t N>
std::string_view name_of(E value, const EnumNames<E, N>& names) {
  for (const auto& [v, name] : names) {
    if (v == value) return name;
  }
  return "unknown";
}

/// The value named `name`; throws std::invalid_argument "unknown <what> 'name' (expected a, b or
/// c)".
template <typename E, std::size_t N>
E value_named(std::string_view name, const EnumNames<E, N>& names, std::string_view what) {
  std::string expected;
  for (std::size_t i = 0; i < N; ++i) {
    if (names[i].second == name) return names[i].first;
    expected += cat(i == 0 ? "" : (i + 1 == N ? " or " : ", "), names[i].second);
  }
  throw std::invalid_argument(cat("unknown ", what, " '", name, "' (expected ", expected, ")"));
}

}  // namespace vantage
