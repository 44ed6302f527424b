#pragma once
/// @file
/// The PLY format (Stanford polygon files): one reader for every PLY Vantage reads (point clouds,
/// meshes) and the header every PLY it writes starts with.

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vantage/io/format_parsing.hpp"

namespace vantage {

/// The encodings of a PLY body.
enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

/// A property of an element: one scalar, or a list of scalars preceded by its length.
struct PlyProperty {
  std::string name;
  ScalarType type{'F', 4};  ///< of the value, or of a list's items
  bool is_list = false;
  ScalarType count_type{'U', 1};  ///< of a list's length
};

/// An element of the header: `count` instances, each holding `properties` in order.
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;

  /// Index of the list property (with `list`) or scalar property called `property`.
  std::optional<std::size_t> find(std::string_view property, bool list = false) const;
};

/// One instance of an element as read: the values of each of its properties.
class PlyRecord {
 public:
  /// The value of scalar property `k`.
  double scalar(std::size_t k) const { return values_[begin_[k]]; }
  /// The items of list property `k`.
  std::span<const double> list(std::size_t k) const {
    return std::span<const double>(values_).subspan(begin_[k], begin_[k + 1] - begin_[k]);
  }

 private:
  friend class PlyReader;
  std::vector<double> values_;
  std::vector<std::size_t> begin_;  ///< where each property's values start; one more at the end
};

/// Reads PLY held in memory: ascii, binary_little_endian or binary_big_endian; the scalar types
/// char, uchar, short, ushort, int, uint, float and double (also as int8 … float64); any
/// elements, scalar and list properties. Every problem throws FormatError with one line saying
/// what and where (the line, or the element), without the file's name.
///
/// NOTE: Vantage reads PLY itself. Debian 12 packages no C++ PLY library (tinyply, happly and
/// rply are not in its archive; `apt-cache search` finds only python3-rply, an unrelated parser
/// generator), PCL 1.13's reader turns a non-numeric ASCII value into 0 without a word, and
/// assimp 5.2's hangs on a truncated PLY header and crashes on some truncated bodies; a corrupt
/// file must give one line, never a crash, a hang or invented data.
class PlyReader {
 public:
  /// Parses and checks the header of `bytes`, which must outlive the reader: a `ply` first line,
  /// one format line, elements and their properties (`comment` and `obj_info` skipped), and
  /// `end_header`. Refuses before any allocation counts that cannot fit the bytes that follow
  /// (a binary instance needs the sizes of its scalars and list lengths, an ASCII one a line).
  explicit PlyReader(std::string_view bytes);
  /// A temporary string would be gone before the reader reads a byte (read() walks `bytes` again):
  /// refused at compile time. Keep the bytes in a variable that outlives the reader.
  template <typename String>
  requires std::same_as<String, std::string>
  explicit PlyReader(String&& temporary) = delete;

  PlyFormat format() const { return format_; }
  const std::vector<PlyElement>& elements() const { return elements_; }
  /// Index of the first element called `name`.
  std::optional<std::size_t> find(std::string_view name) const;

  /// Called for each instance read: the element's index, the instance's index, its values.
  using Visitor = std::function<void(std::size_t, std::uint64_t, const PlyRecord&)>;

  /// Reads the body's elements in file order up to and including element `last`, calling
  /// `visit` for every instance. An ASCII instance is one line; its integral values must be whole
  /// numbers. When `last` is the file's last element, more data after it (bytes, or non-blank
  /// lines) is an error; otherwise the rest is not read.
  void read(std::size_t last, const Visitor& visit) const;

 private:
  void read_ascii(std::size_t last, const Visitor& visit) const;
  void read_binary(std::size_t last, const Visitor& visit) const;
  void check_counts() const;

  std::string_view bytes_;
  PlyFormat format_ = PlyFormat::kAscii;
  std::vector<PlyElement> elements_;
  std::size_t body_ = 0;  ///< first byte after end_header
  int header_lines_ = 0;  ///< lines up to and including end_header
};

/// The header of a PLY file (version 1.0) with `comments` and `elements`, `end_header` included.
std::string ply_header(PlyFormat format, const std::vector<std::string>& comments,
                       const std::vector<PlyElement>& elements);

}  // namespace vantage
