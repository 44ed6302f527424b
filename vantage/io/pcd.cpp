#include "vantage/io/detail/pcd.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "vantage/io/format_parsing.hpp"
#include "vantage/map/grid_spec.hpp"
#include "vantage/util/text.hpp"

namespace vantage::detail {
namespace {

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

/// The header's keys, as read up to and including its DATA line.
struct PcdHeader {
  std::vector<std::string> names;
  std::vector<int> sizes, counts;
  std::vector<char> kinds;
  std::optional<std::uint64_t> width, height, declared_points;
  std::optional<Eigen::Isometry3d> viewpoint;
  std::string data;
};

/// A VIEWPOINT line's tx ty tz qw qx qy qz as a pose.
Eigen::Isometry3d viewpoint_pose(const std::vector<std::string_view>& values, int n) {
  if (values.size() != 7) {
    throw FormatError(
        cat("line ", n, ": VIEWPOINT takes 7 numbers (tx ty tz qw qx qy qz), got ", values.size()));
  }
  double v[7];
  for (std::size_t i = 0; i < 7; ++i) {
    const auto value = parse_number(values[i]);
    if (!value || !std::isfinite(*value)) {
      throw FormatError(cat("line ", n, ": VIEWPOINT value ", i + 1, " is not a finite number"));
    }
    v[i] = *value;
  }
  // NOTE: a sensor 1e300 m away is no pose (issue 53: it was mapped, with a warning that its
  // points missed the roi).
  if (std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2])}) > kMaxWorldCoordinate) {
    throw FormatError(cat("line ", n, ": the VIEWPOINT's position (", v[0], ", ", v[1], ", ", v[2],
                          ") m lies farther from the origin than the ", kMaxWorldCoordinate,
                          " m a world coordinate may"));
  }
  const Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
  // NOTE: writers print the quaternion with a few digits; a norm far from 1 is not a rotation.
  if (std::abs(q.norm() - 1.0) > 1e-3) {
    throw FormatError(cat("line ", n, ": the VIEWPOINT quaternion (", v[3], ", ", v[4], ", ", v[5],
                          ", ", v[6], ") has norm ", q.norm(), ", not 1"));
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = q.normalized().toRotationMatrix();
  pose.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  return pose;
}

/// A VIEWPOINT line for a pose, to the last digit.
std::string fmt_viewpoint(const Eigen::Vector3d& t, const Eigen::Quaterniond& q) {
  std::ostringstream out;
  out.precision(17);
  out << "VIEWPOINT " << t.x() << ' ' << t.y() << ' ' << t.z() << ' ' << q.w() << ' ' << q.x()
      << ' ' << q.y() << ' ' << q.z() << '\n';
  return out.str();
}

/// Reads the header's lines up to and including DATA.
PcdHeader parse_header(Lines& lines) {
  PcdHeader h;
  while (h.data.empty()) {
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
        const auto value = parse_count(v);
        if (!value || *value < 1 || *value > std::numeric_limits<int>::max()) {
          throw FormatError(cat("line ", n, ": ", key, " value '", printable(v, 40),
                                "' is not a positive integer"));
        }
        out.push_back(static_cast<int>(*value));
      }
      return out;
    };
    if (key == "VERSION") {
      continue;
    } else if (key == "VIEWPOINT") {
      h.viewpoint = viewpoint_pose(values, n);
    } else if (key == "FIELDS" || key == "COLUMNS") {
      h.names.assign(values.begin(), values.end());
    } else if (key == "SIZE") {
      h.sizes = ints();
    } else if (key == "COUNT") {
      h.counts = ints();
    } else if (key == "TYPE") {
      h.kinds.clear();
      for (const std::string_view v : values) {
        if (v != "F" && v != "I" && v != "U") {
          throw FormatError(cat("line ", n, ": TYPE '", printable(v, 40), "' is not F, I or U"));
        }
        h.kinds.push_back(v.front());
      }
    } else if (key == "WIDTH") {
      h.width = count_at(one(), n, "WIDTH");
    } else if (key == "HEIGHT") {
      h.height = count_at(one(), n, "HEIGHT");
    } else if (key == "POINTS") {
      h.declared_points = count_at(one(), n, "POINTS");
    } else if (key == "DATA") {
      h.data = one();
      if (h.data != "ascii" && h.data != "binary" && h.data != "binary_compressed") {
        throw FormatError(cat("line ", n, ": DATA '", printable(h.data, 40),
                              "' is not ascii, binary or binary_compressed"));
      }
    } else {
      throw FormatError(cat("line ", n, ": unknown PCD header key '", printable(key, 40), "'"));
    }
  }
  return h;
}

/// Where a point's values lie, read off a checked header.
struct PcdLayout {
  std::vector<PcdField> fields;
  std::size_t step = 0;  ///< bytes a point
  int values_per_point = 0;
  std::size_t xyz[3] = {0, 0, 0};  ///< the fields x, y and z
  std::uint64_t num_points = 0;
};

/// The layout `header` describes, checked: as many SIZE, TYPE and COUNT values as FIELDS, each a
/// supported scalar, WIDTH x HEIGHT points, fields x, y and z of one value each, some points.
PcdLayout layout_of(PcdHeader& header) {
  std::vector<std::string>& names = header.names;
  std::vector<int>& sizes = header.sizes;
  std::vector<int>& counts = header.counts;
  std::vector<char>& kinds = header.kinds;
  const std::optional<std::uint64_t> width = header.width, height = header.height,
                                     declared_points = header.declared_points;
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
  PcdLayout layout;
  layout.num_points = declared_points.value_or(*width * h);
  if (layout.num_points != *width * h) {
    throw FormatError(cat("POINTS ", layout.num_points, " is not WIDTH x HEIGHT = ", *width * h));
  }
  for (std::size_t f = 0; f < names.size(); ++f) {
    const PcdField field{names[f], {kinds[f], sizes[f]}, counts[f], layout.step};
    if (!field.type.valid()) {
      throw FormatError(cat("field '", field.name, "' has TYPE ", field.type.kind, " with SIZE ",
                            field.type.size, ", which is not a supported scalar"));
    }
    layout.step +=
        static_cast<std::size_t>(field.type.size) * static_cast<std::size_t>(field.count);
    layout.values_per_point += field.count;
    layout.fields.push_back(field);
  }
  const std::vector<PcdField>& fields = layout.fields;
  for (int a = 0; a < 3; ++a) {
    const std::string_view name = std::string_view("xyz").substr(static_cast<std::size_t>(a), 1);
    const auto it = std::find_if(fields.begin(), fields.end(),
                                 [&](const PcdField& f) { return f.name == name; });
    if (it == fields.end()) throw FormatError(cat("the PCD file has no field '", name, "'"));
    if (it->count != 1) throw FormatError(cat("field '", name, "' has COUNT ", it->count));
    layout.xyz[a] = static_cast<std::size_t>(it - fields.begin());
  }
  if (layout.num_points == 0) throw FormatError("the cloud is empty");
  return layout;
}

/// DATA ascii: a line of values a point.
PointCloud read_ascii_points(Lines& lines, const PcdLayout& layout) {
  const std::vector<PcdField>& fields = layout.fields;
  const std::uint64_t num_points = layout.num_points;
  PointCloud cloud;
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
    if (tokens.size() != static_cast<std::size_t>(layout.values_per_point)) {
      throw FormatError(cat("line ", lines.number(), ": expected ", layout.values_per_point,
                            " values, found ", tokens.size()));
    }
    Eigen::Vector3d p;
    for (std::size_t t = 0; t < tokens.size(); ++t) {
      const double value = number_at(tokens[t], lines.number());
      for (int a = 0; a < 3; ++a) {
        if (t == column[layout.xyz[a]]) p[a] = value;
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

/// DATA binary_compressed: the size words and the LZF data after them, decompressed into
/// `decompressed`, which the returned view is of.
std::string_view decompress_body(std::string_view body, const PcdLayout& layout,
                                 std::vector<char>& decompressed) {
  const std::uint64_t num_points = layout.num_points;
  const std::size_t step = layout.step;
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
  return std::string_view(decompressed.data(), decompressed.size());
}

/// DATA binary (a point's values together) and binary_compressed (a field's values together).
PointCloud read_binary_points(std::string_view body, const PcdLayout& layout, bool compressed) {
  const std::uint64_t num_points = layout.num_points;
  const std::size_t step = layout.step;
  std::vector<char> decompressed;
  const bool field_major = compressed;
  if (compressed) {
    body = decompress_body(body, layout, decompressed);
  } else if (num_points > body.size() / step || body.size() != num_points * step) {
    throw FormatError(cat("binary data holds ", body.size(), " bytes, expected ", num_points,
                          " points x ", step, " bytes"));
  }
  PointCloud cloud;
  cloud.resize(num_points);
  for (std::size_t i = 0; i < num_points; ++i) {
    for (int a = 0; a < 3; ++a) {
      const PcdField& f = layout.fields[layout.xyz[a]];
      const std::size_t at = field_major
                                 ? f.offset * num_points + i * static_cast<std::size_t>(f.type.size)
                                 : i * step + f.offset;
      cloud[i][a] = decode_scalar(body.data() + at, f.type, false);
    }
  }
  return cloud;
}

}  // namespace

std::optional<Eigen::Isometry3d> parse_pcd_viewpoint(std::string_view bytes) {
  Lines lines(bytes);
  return parse_header(lines).viewpoint;
}

PointCloud parse_pcd(std::string_view bytes) {
  Lines lines(bytes);
  PcdHeader header = parse_header(lines);
  const PcdLayout layout = layout_of(header);
  if (header.data == "ascii") return read_ascii_points(lines, layout);
  return read_binary_points(lines.rest(), layout, header.data == "binary_compressed");
}

std::string pcd_header(std::size_t n, const std::optional<Eigen::Isometry3d>& viewpoint) {
  const Eigen::Isometry3d pose = viewpoint.value_or(Eigen::Isometry3d::Identity());
  const Eigen::Vector3d t = pose.translation();
  const Eigen::Quaterniond q(pose.linear());
  return cat("# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z\n",
             "SIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH ", n, "\nHEIGHT 1\n", fmt_viewpoint(t, q),
             "POINTS ", n, "\nDATA binary\n");
}

}  // namespace vantage::detail
