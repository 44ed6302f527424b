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

/// `text` safe to put into a one-line message: a byte that is not printable ASCII or part of
/// valid UTF-8 becomes \xNN, and text beyond `max_chars` bytes is cut, ending in "...". For
/// tokens echoed from a file, which may be binary.
inline std::string printable(std::string_view text, std::size_t max_chars = 80) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  std::size_t i = 0;
  while (i < text.size() && out.size() < max_chars) {
    const auto c = static_cast<unsigned char>(text[i]);
    // The length of the UTF-8 sequence that starts here, 0 when it is not one.
    std::size_t n = c >= 0x20 && c < 0x7f ? 1 : 0;
    if (c >= 0xc2 && c <= 0xf4) {
      const std::size_t want = c < 0xe0 ? 2 : (c < 0xf0 ? 3 : 4);
      n = want;
      for (std::size_t k = 1; k < want; ++k) {
        if (i + k >= text.size() || (static_cast<unsigned char>(text[i + k]) & 0xc0) != 0x80) n = 0;
      }
    }
    if (n > 0) {
      out.append(text.substr(i, n));
      i += n;
    } else {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
      ++i;
    }
  }
  if (i < text.size()) out += "...";
  return out;
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
