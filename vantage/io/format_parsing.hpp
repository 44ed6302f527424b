#pragma once
/// @file
/// What the file-format readers (PCD, PLY, YAML) share: their error type, what a path is,
/// lines and tokens of text, strict numbers, and binary scalars.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace vantage {

/// A problem inside a file, said in one line without the file's name (the caller, which knows
/// the path, prefixes it).
struct FormatError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Why `path` cannot be read as a regular file, said as what it is: "no such file", "is a
/// directory, not a file", "is a FIFO, not a regular file", "is a character device, not a regular
/// file", "is a symlink loop", "permission denied"...; empty when it is a regular file.
std::string not_a_readable_file(const std::filesystem::path& path);

/// (Reading a file whole: read_input_file, vantage/io/input_file.hpp, which also bounds its size.)

/// Lines of a text, counted from 1, with their '\n' and a trailing '\r' removed.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  /// Resumes at byte `position`, after `lines_before` lines.
  Lines(std::string_view text, std::size_t position, int lines_before)
      : text_(text), position_(position), number_(lines_before) {}

  /// The next line, or nothing at the end of the text.
  std::optional<std::string_view> next();
  /// The next line that holds something other than white space.
  std::optional<std::string_view> next_nonblank();
  int number() const { return number_; }              ///< of the line last returned
  std::size_t position() const { return position_; }  ///< first byte not yet read
  std::string_view rest() const { return text_.substr(position_); }

 private:
  std::string_view text_;
  std::size_t position_ = 0;
  int number_ = 0;
};

/// The tokens of a line separated by white space.
std::vector<std::string_view> split(std::string_view line);

/// The whole token as a double (an optional leading '+'; "nan" and "inf" are numbers here, the
/// caller decides about them), or nothing when it is not exactly a number.
std::optional<double> parse_number(std::string_view token);

/// The whole token as an unsigned 64-bit count, or nothing.
std::optional<std::uint64_t> parse_count(std::string_view token);

/// parse_number, or FormatError "line N: 'token' is not a number".
double number_at(std::string_view token, int line);

/// parse_count, or FormatError "line N: <what> 'token' is not a count".
std::uint64_t count_at(std::string_view token, int line, std::string_view what);

/// A binary scalar: kind 'F' (float), 'I' (signed) or 'U' (unsigned), and its size in bytes.
struct ScalarType {
  char kind = 'F';
  int size = 4;

  /// F of 4 or 8 bytes, I and U of 1, 2, 4 or 8.
  bool valid() const;
  bool integral() const { return kind != 'F'; }
};

/// The scalar at `p`, stored little-endian, or big-endian with `swap`.
double decode_scalar(const char* p, const ScalarType& type, bool swap);

}  // namespace vantage
