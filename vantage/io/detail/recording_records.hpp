#pragma once
/// @file
/// What the two recording readers (rosbag.cpp, mcap.cpp) share: little-endian reads from a
/// region of a file, and how what they find wrong becomes RecordingDamage (issue 53).

#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>

#include "vantage/io/recording_formats.hpp"
#include "vantage/util/text.hpp"

namespace vantage::detail {

/// What a reader refuses that is no damage: a compression or a version it does not read.
struct Unsupported : FormatError {
  using FormatError::FormatError;
};

/// Little-endian reads from a region of a file; `base` is the region's offset in the file (in
/// the decompressed chunk, for a chunk's records), for messages.
class Cursor {
 public:
  Cursor(std::string_view bytes, std::uint64_t base, std::string_view where)
      : bytes_(bytes), base_(base), where_(where) {}
  bool done() const { return pos_ >= bytes_.size(); }
  std::uint64_t offset() const { return base_ + pos_; }
  std::uint64_t left() const { return bytes_.size() - pos_; }
  template <class T>
  T scalar(std::string_view what) {
    const std::string_view raw = take(sizeof(T), what);
    T value;
    std::memcpy(&value, raw.data(), sizeof(T));  // NOTE: both formats are little-endian.
    return value;
  }
  /// The scalar `skip` bytes ahead, or nothing when the region ends before it; nothing is taken.
  template <class T>
  std::optional<T> peek(std::uint64_t skip) const {
    if (skip > left() || sizeof(T) > left() - skip) return std::nullopt;
    T value;
    std::memcpy(&value, bytes_.data() + pos_ + skip, sizeof(T));
    return value;
  }
  std::string_view take(std::uint64_t n, std::string_view what) {
    if (n > bytes_.size() - pos_) {
      throw FormatError(cat(what, " at byte ", offset(), where_, " runs past the end (", n,
                            " bytes, ", bytes_.size() - pos_, " left)"));
    }
    const std::string_view out = bytes_.substr(pos_, static_cast<std::size_t>(n));
    pos_ += static_cast<std::size_t>(n);
    return out;
  }
  std::string_view where() const { return where_; }
  /// What is left, all of it.
  std::string_view rest() {
    const std::string_view out = bytes_.substr(pos_);
    pos_ = bytes_.size();
    return out;
  }

 private:
  std::string_view bytes_;
  std::size_t pos_ = 0;
  std::uint64_t base_ = 0;
  std::string where_;  // NOTE: owned: a Cursor is often made with a cat(...) temporary
};

/// The damage of a record of the file that runs past its end: `claimed` bytes from `at`, `left`
/// there.
[[noreturn]] inline void cut_short(std::uint64_t at, std::uint64_t claimed, std::uint64_t left) {
  throw RecordingDamage(
      at, cat("the record at byte ", at, " runs past the file's end (it claims ", claimed,
              " bytes, ", left, " are there): the file is cut short or the length damaged"));
}

/// Runs `read` on the record at `at`; what it finds wrong, but for what Vantage does not read, is
/// damage there.
template <class Read>
void as_damage(std::uint64_t at, Read read) {
  try {
    read();
  } catch (const RecordingDamage&) {
    throw;
  } catch (const Unsupported&) {
    throw;
  } catch (const FormatError& e) {
    throw RecordingDamage(at, e.what());
  }
}

}  // namespace vantage::detail
