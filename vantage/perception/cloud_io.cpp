#include "vantage/perception/cloud_io.hpp"

// NOTE: PCL's readers are not used. PCL 1.13's PCDReader crashes (SIGSEGV) on a file that is not
// a PCD file, and both its PCD and PLY readers turn a non-numeric ASCII value into 0 without a
// word; this module must name the file and never return a partial or invented cloud. Nor is
// pcl_io linked for its LZF decoder: it drags some 60 shared libraries (VTK, Qt) into every
// program that reads a cloud, so binary_compressed PCD data is decoded here (lzf_decompress).

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "vantage/io/atomic_file.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {
namespace fs = std::filesystem;

static_assert(std::endian::native == std::endian::little,
              "PCD binary data and PLY binary_little_endian are read by copying bytes");

/// A problem inside a file; read_point_cloud prefixes the file's name.
struct FormatError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

enum class Format { kPcd, kPly };

Format format_of(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".pcd") return Format::kPcd;
  if (extension == ".ply") return Format::kPly;
  throw std::invalid_argument(cat(path.string(), ": unsupported point-cloud format '", extension,
                                  "' (expected .pcd or .ply)"));
}

std::string read_whole_file(const fs::path& path) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) {
    throw FormatError(fs::exists(path, error) ? "not a regular file" : "no such file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FormatError("cannot open for reading");
  std::string text;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof(buffer)) || in.gcount() > 0) text.append(buffer, in.gcount());
  if (in.bad()) throw FormatError("read failed");
  return text;
}

// ---- scalars -------------------------------------------------------------------------------

/// A binary scalar: kind 'F' (float), 'I' (signed) or 'U' (unsigned), and its size in bytes.
struct ScalarType {
  char kind = 'F';
  int size = 4;
};

bool valid_scalar(const ScalarType& t) {
  if (t.kind == 'F') return t.size == 4 || t.size == 8;
  if (t.kind == 'I' || t.kind == 'U')
    return t.size == 1 || t.size == 2 || t.size == 4 || t.size == 8;
  return false;
}

/// The value at `p`, stored little-endian or (with `swap`) big-endian.
double decode(const char* p, const ScalarType& t, bool swap) {
  unsigned char b[8];
  std::memcpy(b, p, static_cast<std::size_t>(t.size));
  if (swap) std::reverse(b, b + t.size);
  const auto as = [&b]<typename T>(T) {
    T value;
    std::memcpy(&value, b, sizeof(T));
    return static_cast<double>(value);
  };
  switch (t.kind) {
    case 'F':
      return t.size == 4 ? as(float{}) : as(double{});
    case 'I':
      switch (t.size) {
        case 1:
          return as(std::int8_t{});
        case 2:
          return as(std::int16_t{});
        case 4:
          return as(std::int32_t{});
        default:
          return as(std::int64_t{});
      }
    default:
      switch (t.size) {
        case 1:
          return as(std::uint8_t{});
        case 2:
          return as(std::uint16_t{});
        case 4:
          return as(std::uint32_t{});
        default:
          return as(std::uint64_t{});
      }
  }
}

// ---- text ----------------------------------------------------------------------------------

/// Lines of a text, counted from 1, with their '\n' and a trailing '\r' removed.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}

  std::optional<std::string_view> next() {
    if (position_ >= text_.size()) return std::nullopt;
    const std::size_t end = text_.find('\n', position_);
    const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
    std::string_view line = text_.substr(position_, stop - position_);
    position_ = end == std::string_view::npos ? text_.size() : end + 1;
    ++number_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
  }
  /// The next line that holds something other than white space.
  std::optional<std::string_view> next_nonblank() {
    while (const auto line = next()) {
      if (line->find_first_not_of(" \t\r\f\v") != std::string_view::npos) return line;
    }
    return std::nullopt;
  }
  int number() const { return number_; }              ///< of the line last returned
  std::size_t position() const { return position_; }  ///< first byte not yet read
  std::string_view rest() const { return text_.substr(position_); }

 private:
  std::string_view text_;
  std::size_t position_ = 0;
  int number_ = 0;
};

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

template <typename T>
std::optional<T> parse_integer(std::string_view token) {
  T value{};
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return value;
}

double number_at(std::string_view token, int line) {
  const auto value = parse_number(token);
  if (!value) throw FormatError(cat("line ", line, ": '", token, "' is not a number"));
  return *value;
}

std::uint64_t count_at(std::string_view token, int line, std::string_view what) {
  const auto value = parse_integer<std::uint64_t>(token);
  if (!value) {
    throw FormatError(cat("line ", line, ": ", what, " '", token, "' is not a count"));
  }
  return *value;
}

/// Refuses a count of items that could not fit in `available` bytes, before reserving for it.
void check_fits(std::uint64_t items, std::uint64_t min_bytes_each, std::size_t available,
                std::string_view what) {
  if (min_bytes_each > 0 && items > available / min_bytes_each) {
    throw FormatError(
        cat("declares ", items, " ", what, " but holds only ", available, " bytes of data"));
  }
}

/// Decodes LZF data (the compression of PCD's DATA binary_compressed) into exactly `out.size()`
/// bytes; false when the data is corrupt or does not decode to that size. The format is a
/// sequence of runs, each starting with a control byte c: c < 32 copies the next c + 1 bytes;
/// otherwise it repeats L bytes from D back in the output, where L = (c >> 5) + 2 (when c >> 5
/// is 7, a further byte is added to L) and D = ((c & 31) << 8) + next byte + 1.
bool lzf_decompress(std::string_view in, std::vector<char>& out) {
  std::size_t i = 0, o = 0;
  while (i < in.size()) {
    const auto c = static_cast<unsigned char>(in[i++]);
    if (c < 32) {
      const std::size_t run = c + 1u;
      if (in.size() - i < run || out.size() - o < run) return false;
      std::memcpy(out.data() + o, in.data() + i, run);
      i += run;
      o += run;
      continue;
    }
    std::size_t length = c >> 5;
    if (length == 7) {
      if (i >= in.size()) return false;
      length += static_cast<unsigned char>(in[i++]);
    }
    length += 2;
    if (i >= in.size()) return false;
    const std::size_t distance = ((c & 31u) << 8) + static_cast<unsigned char>(in[i++]) + 1;
    if (distance > o || out.size() - o < length) return false;
    // Byte by byte: a repeat may overlap the bytes it is producing.
    for (std::size_t k = 0; k < length; ++k, ++o) out[o] = out[o - distance];
  }
  return o == out.size();
}

// ---- PCD -----------------------------------------------------------------------------------

struct PcdField {
  std::string name;
  ScalarType type;
  int count = 1;
  std::size_t offset = 0;  // within a point [bytes]
};

PointCloud parse_pcd(std::string_view text) {
  Lines lines(text);
  std::vector<std::string> names;
  std::vector<int> sizes, counts;
  std::vector<char> kinds;
  std::optional<std::uint64_t> width, height, declared_points;
  std::string data;
  while (data.empty()) {
    const auto line = lines.next();
    if (!line) throw FormatError("not a PCD file: the header has no DATA line");
    const std::vector<std::string_view> tokens = split(*line);
    if (tokens.empty() || tokens[0].front() == '#') continue;
    const std::string_view key = tokens[0];
    const std::vector<std::string_view> values(tokens.begin() + 1, tokens.end());
    const int n = lines.number();
    const auto one = [&]() {
      if (values.size() != 1) throw FormatError(cat("line ", n, ": ", key, " takes one value"));
      return values[0];
    };
    const auto ints = [&]() {
      std::vector<int> out;
      for (const std::string_view v : values) {
        const auto value = parse_integer<int>(v);
        if (!value || *value < 1) {
          throw FormatError(
              cat("line ", n, ": ", key, " value '", v, "' is not a positive integer"));
        }
        out.push_back(*value);
      }
      return out;
    };
    if (key == "VERSION" || key == "VIEWPOINT") {
      continue;
    } else if (key == "FIELDS" || key == "COLUMNS") {
      names.assign(values.begin(), values.end());
    } else if (key == "SIZE") {
      sizes = ints();
    } else if (key == "COUNT") {
      counts = ints();
    } else if (key == "TYPE") {
      kinds.clear();
      for (const std::string_view v : values) {
        if (v != "F" && v != "I" && v != "U") {
          throw FormatError(cat("line ", n, ": TYPE '", v, "' is not F, I or U"));
        }
        kinds.push_back(v.front());
      }
    } else if (key == "WIDTH") {
      width = count_at(one(), n, "WIDTH");
    } else if (key == "HEIGHT") {
      height = count_at(one(), n, "HEIGHT");
    } else if (key == "POINTS") {
      declared_points = count_at(one(), n, "POINTS");
    } else if (key == "DATA") {
      data = one();
      if (data != "ascii" && data != "binary" && data != "binary_compressed") {
        throw FormatError(
            cat("line ", n, ": DATA '", data, "' is not ascii, binary or binary_compressed"));
      }
    } else {
      throw FormatError(cat("line ", n, ": unknown PCD header key '", key, "'"));
    }
  }

  if (names.empty()) throw FormatError("the PCD header has no FIELDS");
  if (counts.empty()) counts.assign(names.size(), 1);
  if (sizes.size() != names.size() || kinds.size() != names.size() ||
      counts.size() != names.size()) {
    throw FormatError(cat("the PCD header has ", names.size(), " FIELDS but ", sizes.size(),
                          " SIZE, ", kinds.size(), " TYPE and ", counts.size(), " COUNT values"));
  }
  if (!width) throw FormatError("the PCD header has no WIDTH");
  const std::uint64_t h = height.value_or(1);
  if (*width != 0 && h > std::numeric_limits<std::uint64_t>::max() / *width) {
    throw FormatError("WIDTH x HEIGHT overflows");
  }
  const std::uint64_t num_points = declared_points.value_or(*width * h);
  if (num_points != *width * h) {
    throw FormatError(cat("POINTS ", num_points, " is not WIDTH x HEIGHT = ", *width * h));
  }

  std::vector<PcdField> fields;
  std::size_t step = 0;
  int values_per_point = 0;
  for (std::size_t f = 0; f < names.size(); ++f) {
    const PcdField field{names[f], {kinds[f], sizes[f]}, counts[f], step};
    if (!valid_scalar(field.type)) {
      throw FormatError(cat("field '", field.name, "' has TYPE ", field.type.kind, " with SIZE ",
                            field.type.size, ", which is not a supported scalar"));
    }
    step += static_cast<std::size_t>(field.type.size) * static_cast<std::size_t>(field.count);
    values_per_point += field.count;
    fields.push_back(field);
  }
  std::size_t xyz[3];
  for (int a = 0; a < 3; ++a) {
    const std::string_view name = std::string_view("xyz").substr(static_cast<std::size_t>(a), 1);
    const auto it = std::find_if(fields.begin(), fields.end(),
                                 [&](const PcdField& f) { return f.name == name; });
    if (it == fields.end()) throw FormatError(cat("the PCD file has no field '", name, "'"));
    if (it->count != 1) throw FormatError(cat("field '", name, "' has COUNT ", it->count));
    xyz[a] = static_cast<std::size_t>(it - fields.begin());
  }
  if (num_points == 0) throw FormatError("the cloud is empty");

  PointCloud cloud;
  if (data == "ascii") {
    cloud.reserve(std::min<std::uint64_t>(num_points, lines.rest().size() / 2 + 1));
    // Column of each field's first value on a line.
    std::vector<std::size_t> column(fields.size());
    for (std::size_t f = 1; f < fields.size(); ++f) {
      column[f] = column[f - 1] + static_cast<std::size_t>(fields[f - 1].count);
    }
    for (std::uint64_t i = 0; i < num_points; ++i) {
      const auto line = lines.next_nonblank();
      if (!line) {
        throw FormatError(cat("ends after ", i, " of the ", num_points, " points it declares"));
      }
      const std::vector<std::string_view> tokens = split(*line);
      if (tokens.size() != static_cast<std::size_t>(values_per_point)) {
        throw FormatError(cat("line ", lines.number(), ": expected ", values_per_point,
                              " values, found ", tokens.size()));
      }
      Eigen::Vector3d p;
      for (std::size_t t = 0; t < tokens.size(); ++t) {
        const double value = number_at(tokens[t], lines.number());
        for (int a = 0; a < 3; ++a) {
          if (t == column[xyz[a]]) p[a] = value;
        }
      }
      cloud.push_back(p);
    }
    if (lines.next_nonblank()) {
      throw FormatError(
          cat("line ", lines.number(), ": more points than the ", num_points, " declared"));
    }
    return cloud;
  }

  std::string_view body = lines.rest();
  std::vector<char> decompressed;
  bool field_major = false;  // binary_compressed stores all points' values of a field together
  if (data == "binary_compressed") {
    if (body.size() < 8) throw FormatError("binary_compressed data has no size words");
    std::uint32_t sizes_words[2];
    std::memcpy(sizes_words, body.data(), 8);
    const std::uint32_t compressed = sizes_words[0], uncompressed = sizes_words[1];
    if (body.size() - 8 < compressed) {
      throw FormatError(cat("binary_compressed data holds ", body.size() - 8,
                            " bytes, its size word says ", compressed));
    }
    check_fits(num_points, step, uncompressed, "points");
    if (uncompressed != num_points * step) {
      throw FormatError(cat("binary_compressed data uncompresses to ", uncompressed,
                            " bytes, expected ", num_points, " points x ", step, " bytes"));
    }
    // NOTE: one LZF run of 3 bytes yields at most 264; a larger ratio is a lie, refused before
    // the allocation it asks for.
    if (uncompressed / 88 > compressed) throw FormatError("binary_compressed data is corrupt");
    decompressed.resize(uncompressed);
    if (!lzf_decompress(body.substr(8, compressed), decompressed)) {
      throw FormatError("binary_compressed data is corrupt");
    }
    body = std::string_view(decompressed.data(), decompressed.size());
    field_major = true;
  } else {
    if (num_points > body.size() / step || body.size() != num_points * step) {
      throw FormatError(cat("binary data holds ", body.size(), " bytes, expected ", num_points,
                            " points x ", step, " bytes"));
    }
  }
  cloud.resize(num_points);
  for (std::size_t i = 0; i < num_points; ++i) {
    for (int a = 0; a < 3; ++a) {
      const PcdField& f = fields[xyz[a]];
      const std::size_t at = field_major
                                 ? f.offset * num_points + i * static_cast<std::size_t>(f.type.size)
                                 : i * step + f.offset;
      cloud[i][a] = decode(body.data() + at, f.type, false);
    }
  }
  return cloud;
}

// ---- PLY -----------------------------------------------------------------------------------

struct PlyProperty {
  std::string name;
  ScalarType type;
  bool is_list = false;
  ScalarType count_type;  // of a list
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

std::optional<ScalarType> ply_type(std::string_view name) {
  if (name == "char" || name == "int8") return ScalarType{'I', 1};
  if (name == "uchar" || name == "uint8") return ScalarType{'U', 1};
  if (name == "short" || name == "int16") return ScalarType{'I', 2};
  if (name == "ushort" || name == "uint16") return ScalarType{'U', 2};
  if (name == "int" || name == "int32") return ScalarType{'I', 4};
  if (name == "uint" || name == "uint32") return ScalarType{'U', 4};
  if (name == "float" || name == "float32") return ScalarType{'F', 4};
  if (name == "double" || name == "float64") return ScalarType{'F', 8};
  return std::nullopt;
}

PointCloud parse_ply(std::string_view text) {
  Lines lines(text);
  if (const auto first = lines.next(); !first || *first != "ply") {
    throw FormatError("not a PLY file: the first line is not 'ply'");
  }
  std::string format;
  std::vector<PlyElement> elements;
  for (;;) {
    const auto line = lines.next();
    if (!line) throw FormatError("the PLY header has no end_header line");
    const std::vector<std::string_view> t = split(*line);
    const int n = lines.number();
    if (t.empty() || t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "end_header") break;
    if (t[0] == "format") {
      if (t.size() != 3 ||
          (t[1] != "ascii" && t[1] != "binary_little_endian" && t[1] != "binary_big_endian")) {
        throw FormatError(cat("line ", n, ": unsupported PLY format '", *line, "'"));
      }
      format = t[1];
    } else if (t[0] == "element") {
      if (t.size() != 3) throw FormatError(cat("line ", n, ": expected 'element <name> <count>'"));
      elements.push_back({std::string(t[1]), count_at(t[2], n, "element count"), {}});
    } else if (t[0] == "property") {
      if (elements.empty()) throw FormatError(cat("line ", n, ": property before any element"));
      PlyProperty property;
      if (t.size() == 5 && t[1] == "list") {
        const auto count_type = ply_type(t[2]);
        const auto item_type = ply_type(t[3]);
        if (!count_type || !item_type || count_type->kind == 'F') {
          throw FormatError(cat("line ", n, ": unsupported list types '", t[2], " ", t[3], "'"));
        }
        property = {std::string(t[4]), *item_type, true, *count_type};
      } else if (t.size() == 3) {
        const auto type = ply_type(t[1]);
        if (!type) throw FormatError(cat("line ", n, ": unknown PLY type '", t[1], "'"));
        property = {std::string(t[2]), *type, false, {}};
      } else {
        throw FormatError(cat("line ", n, ": malformed property line"));
      }
      elements.back().properties.push_back(property);
    } else {
      throw FormatError(cat("line ", n, ": unknown PLY header keyword '", t[0], "'"));
    }
  }
  if (format.empty()) throw FormatError("the PLY header has no format line");
  const auto vertex_it = std::find_if(elements.begin(), elements.end(),
                                      [](const PlyElement& e) { return e.name == "vertex"; });
  if (vertex_it == elements.end()) throw FormatError("the PLY file has no vertex element");
  const PlyElement& vertex = *vertex_it;
  std::size_t xyz[3];
  for (int a = 0; a < 3; ++a) {
    const std::string_view name = std::string_view("xyz").substr(static_cast<std::size_t>(a), 1);
    const auto it = std::find_if(vertex.properties.begin(), vertex.properties.end(),
                                 [&](const PlyProperty& p) { return p.name == name; });
    if (it == vertex.properties.end() || it->is_list) {
      throw FormatError(cat("the PLY vertex element has no scalar property '", name, "'"));
    }
    xyz[a] = static_cast<std::size_t>(it - vertex.properties.begin());
  }
  if (vertex.count == 0) throw FormatError("the cloud is empty");
  const bool last = vertex_it + 1 == elements.end();
  PointCloud cloud;

  if (format == "ascii") {
    for (auto e = elements.begin(); e != vertex_it; ++e) {
      for (std::uint64_t i = 0; i < e->count; ++i) {
        if (!lines.next_nonblank()) {
          throw FormatError(cat("ends inside element '", e->name, "'"));
        }
      }
    }
    cloud.reserve(std::min<std::uint64_t>(vertex.count, lines.rest().size() / 2 + 1));
    for (std::uint64_t i = 0; i < vertex.count; ++i) {
      const auto line = lines.next_nonblank();
      if (!line) {
        throw FormatError(cat("ends after ", i, " of the ", vertex.count, " vertices it declares"));
      }
      const std::vector<std::string_view> tokens = split(*line);
      const int n = lines.number();
      std::size_t t = 0;
      Eigen::Vector3d p;
      for (std::size_t k = 0; k < vertex.properties.size(); ++k) {
        std::uint64_t items = 1;
        if (vertex.properties[k].is_list) {
          if (t >= tokens.size()) throw FormatError(cat("line ", n, ": too few values"));
          items = count_at(tokens[t++], n, "list length");
        }
        for (std::uint64_t j = 0; j < items; ++j, ++t) {
          if (t >= tokens.size()) throw FormatError(cat("line ", n, ": too few values"));
          const double value = number_at(tokens[t], n);
          for (int a = 0; a < 3; ++a) {
            if (k == xyz[a]) p[a] = value;
          }
        }
      }
      if (t != tokens.size()) {
        throw FormatError(cat("line ", n, ": ", tokens.size() - t, " values more than declared"));
      }
      cloud.push_back(p);
    }
    if (last && lines.next_nonblank()) {
      throw FormatError(
          cat("line ", lines.number(), ": more vertices than the ", vertex.count, " declared"));
    }
    return cloud;
  }

  const bool swap = format == "binary_big_endian";
  const std::string_view body = lines.rest();
  std::size_t at = 0;
  const auto take = [&](std::size_t bytes, std::string_view element) {
    if (body.size() - at < bytes)
      throw FormatError(cat("binary data ends inside element '", element, "'"));
    const char* p = body.data() + at;
    at += bytes;
    return p;
  };
  // Walks one instance of `e`, handing each scalar property's position to `on_scalar`.
  const auto walk = [&](const PlyElement& e, auto&& on_scalar) {
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const PlyProperty& prop = e.properties[k];
      const auto size = static_cast<std::size_t>(prop.type.size);
      if (!prop.is_list) {
        on_scalar(k, take(size, e.name));
        continue;
      }
      const double items = decode(take(static_cast<std::size_t>(prop.count_type.size), e.name),
                                  prop.count_type, swap);
      if (items < 0) throw FormatError(cat("negative list length in element '", e.name, "'"));
      if (items > static_cast<double>(body.size())) {
        throw FormatError(cat("binary data ends inside element '", e.name, "'"));
      }
      take(static_cast<std::size_t>(items) * size, e.name);
    }
  };
  for (auto e = elements.begin(); e != vertex_it; ++e) {
    for (std::uint64_t i = 0; i < e->count; ++i) walk(*e, [](std::size_t, const char*) {});
  }
  std::size_t min_vertex_bytes = 0;
  for (const PlyProperty& p : vertex.properties) {
    min_vertex_bytes += static_cast<std::size_t>(p.is_list ? p.count_type.size : p.type.size);
  }
  check_fits(vertex.count, min_vertex_bytes, body.size() - at, "vertices");
  cloud.resize(vertex.count);
  for (std::size_t i = 0; i < vertex.count; ++i) {
    walk(vertex, [&](std::size_t k, const char* p) {
      for (int a = 0; a < 3; ++a) {
        if (k == xyz[a]) cloud[i][a] = decode(p, vertex.properties[k].type, swap);
      }
    });
  }
  if (last && at != body.size()) {
    throw FormatError(cat("holds ", body.size() - at, " bytes after its last vertex"));
  }
  return cloud;
}

void check_finite(const PointCloud& cloud) {
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d& p = cloud[i];
    if (!p.allFinite()) {
      throw FormatError(
          cat("point ", i, " has a non-finite coordinate (", p.x(), ", ", p.y(), ", ", p.z(), ")"));
    }
  }
}

// ---- writing -------------------------------------------------------------------------------

std::string pcd_header(std::size_t n) {
  return cat("# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z\n",
             "SIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH ", n, "\nHEIGHT 1\n",
             "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS ", n, "\nDATA binary\n");
}

std::string ply_header(std::size_t n) {
  return cat("ply\nformat binary_little_endian 1.0\ncomment written by vantage\nelement vertex ", n,
             "\nproperty float x\nproperty float y\nproperty float z\nend_header\n");
}

}  // namespace

PointCloud read_point_cloud(const fs::path& path, const CloudReadOptions& options) {
  const Format format = format_of(path);
  try {
    const std::string text = read_whole_file(path);
    PointCloud cloud = format == Format::kPcd ? parse_pcd(text) : parse_ply(text);
    if (options.skip_non_finite) {
      std::erase_if(cloud, [](const Eigen::Vector3d& p) { return !p.allFinite(); });
      if (cloud.empty()) throw FormatError("no point has finite coordinates");
    }
    check_finite(cloud);
    return cloud;
  } catch (const FormatError& e) {
    throw std::runtime_error(cat(path.string(), ": ", e.what()));
  }
}

void write_point_cloud(const fs::path& path, const PointCloud& points) {
  const Format format = format_of(path);
  if (points.empty()) {
    throw std::invalid_argument(cat(path.string(), ": refusing to write an empty point cloud"));
  }
  std::vector<float> packed(3 * points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      const auto value = static_cast<float>(points[i][a]);
      if (!std::isfinite(value)) {
        throw std::invalid_argument(cat(path.string(), ": point ", i, " is not finite as float (",
                                        points[i].x(), ", ", points[i].y(), ", ", points[i].z(),
                                        ")"));
      }
      packed[3 * i + static_cast<std::size_t>(a)] = value;
    }
  }
  const std::string header =
      format == Format::kPcd ? pcd_header(points.size()) : ply_header(points.size());
  write_atomically(path, [&](std::ostream& out) {
    out << header;
    out.write(reinterpret_cast<const char*>(packed.data()),
              static_cast<std::streamsize>(packed.size() * sizeof(float)));
  });
}

}  // namespace vantage
