#include "vantage/io/format_parsing.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cstring>
#include <system_error>
#include <type_traits>

#include "vantage/util/text.hpp"

namespace vantage {
namespace fs = std::filesystem;

std::string not_a_readable_file(const fs::path& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (error) {
    if (error == std::errc::no_such_file_or_directory) return "no such file";
    if (error == std::errc::too_many_symbolic_link_levels) return "is a symlink loop";
    if (error == std::errc::not_a_directory) return "no such file (a part of the path is a file)";
    return error.message();  // permission denied, name too long...
  }
  switch (status.type()) {
    case fs::file_type::regular:
      return {};
    case fs::file_type::not_found:
      return "no such file";
    case fs::file_type::directory:
      return "is a directory, not a file";
    case fs::file_type::fifo:
      return "is a FIFO, not a regular file";
    case fs::file_type::character:
      return "is a character device, not a regular file";
    case fs::file_type::block:
      return "is a block device, not a regular file";
    case fs::file_type::socket:
      return "is a socket, not a regular file";
    default:
      return "is not a regular file";
  }
}

std::optional<std::string_view> Lines::next() {
  if (position_ >= text_.size()) return std::nullopt;
  const std::size_t end = text_.find('\n', position_);
  const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
  std::string_view line = text_.substr(position_, stop - position_);
  position_ = end == std::string_view::npos ? text_.size() : end + 1;
  ++number_;
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

std::optional<std::string_view> Lines::next_nonblank() {
  while (const auto line = next()) {
    if (line->find_first_not_of(" \t\r\f\v") != std::string_view::npos) return line;
  }
  return std::nullopt;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  constexpr std::string_view kSpace = " \t\r\f\v";
  while ((i = line.find_first_not_of(kSpace, i)) != std::string_view::npos) {
    const std::size_t end = std::min(line.find_first_of(kSpace, i), line.size());
    tokens.push_back(line.substr(i, end - i));
    i = end;
  }
  return tokens;
}

std::optional<double> parse_number(std::string_view token) {
  if (token.size() > 1 && token.front() == '+') token.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return value;
}

std::optional<std::uint64_t> parse_count(std::string_view token) {
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return value;
}

double number_at(std::string_view token, int line) {
  const auto value = parse_number(token);
  if (!value)
    throw FormatError(cat("line ", line, ": '", printable(token, 40), "' is not a number"));
  return *value;
}

std::uint64_t count_at(std::string_view token, int line, std::string_view what) {
  const auto value = parse_count(token);
  if (!value)
    throw FormatError(
        cat("line ", line, ": ", what, " '", printable(token, 40), "' is not a count"));
  return *value;
}

bool ScalarType::valid() const {
  if (kind == 'F') return size == 4 || size == 8;
  if (kind == 'I' || kind == 'U') return size == 1 || size == 2 || size == 4 || size == 8;
  return false;
}

namespace {

/// The value of the first of the types T whose kind and size are `t`'s, from bytes `b`.
template <typename... T>
double decode_as_one_of(const unsigned char* b, const ScalarType& t) {
  double value = 0.0;
  const auto decode = [&]<typename U>(U*) {
    const char kind = std::is_floating_point_v<U> ? 'F' : (std::is_signed_v<U> ? 'I' : 'U');
    if (kind != t.kind || t.size != static_cast<int>(sizeof(U))) return false;
    U v;
    std::memcpy(&v, b, sizeof(U));
    value = static_cast<double>(v);
    return true;
  };
  (decode(static_cast<T*>(nullptr)) || ...);
  return value;
}

}  // namespace

double decode_scalar(const char* p, const ScalarType& t, bool swap) {
  static_assert(std::endian::native == std::endian::little,
                "binary scalars are decoded by copying little-endian bytes");
  unsigned char b[8];
  std::memcpy(b, p, static_cast<std::size_t>(t.size));
  if (swap) std::reverse(b, b + t.size);
  return decode_as_one_of<float, double, std::int8_t, std::int16_t, std::int32_t, std::int64_t,
                          std::uint8_t, std::uint16_t, std::uint32_t, std::uint64_t>(b, t);
}

}  // namespace vantage
