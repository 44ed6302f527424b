#include "vantage/io/ros_messages.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "vantage/io/format_parsing.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// Reads a message's fields in order, in either wire format; every read checks the bytes left.
class Wire {
 public:
  Wire(std::string_view data, RosEncoding encoding) : cdr_(encoding == RosEncoding::kCdr) {
    if (cdr_) {
      // NOTE: CDR's encapsulation header: 0 0 is big-endian CDR, 0 1 little-endian.
      if (data.size() < 4) throw FormatError("shorter than CDR's 4-byte encapsulation header");
      if (data[0] != 0 || (data[1] != 0 && data[1] != 1)) {
        throw FormatError(cat("encapsulation kind ", static_cast<int>(data[0]), " ",
                              static_cast<int>(data[1]), " is not plain CDR (0 0 or 0 1)"));
      }
      swap_ = (data[1] == 0) == (std::endian::native == std::endian::little);
      data = data.substr(4);
    }
    data_ = data;
  }

  template <class T>
  T scalar(std::string_view what) {
    align(sizeof(T));
    need(sizeof(T), what);
    std::array<char, sizeof(T)> raw;
    std::memcpy(raw.data(), data_.data() + pos_, sizeof(T));
    if (swap_) std::reverse(raw.begin(), raw.end());
    pos_ += sizeof(T);
    return std::bit_cast<T>(raw);
  }
  double stamp() {
    const double sec = cdr_ ? static_cast<double>(scalar<std::int32_t>("header.stamp.sec"))
                            : static_cast<double>(scalar<std::uint32_t>("header.stamp.sec"));
    const std::uint32_t nsec = scalar<std::uint32_t>("header.stamp.nanosec");
    if (nsec >= 1'000'000'000u) throw FormatError(cat("header.stamp.nanosec ", nsec, " >= 1e9"));
    return sec + nsec * 1e-9;
  }
  RosHeader header() {
    RosHeader h;
    if (!cdr_) scalar<std::uint32_t>("header.seq");
    h.stamp = stamp();
    h.frame_id = string("header.frame_id");
    return h;
  }
  std::string string(std::string_view what) {
    const std::uint32_t n = scalar<std::uint32_t>(what);
    need(n, what);
    std::string_view s = data_.substr(pos_, n);
    pos_ += n;
    if (cdr_) {  // NOTE: CDR counts the terminating null.
      if (s.empty() || s.back() != '\0') {
        throw FormatError(cat(what, " is not a CDR string (no terminating null)"));
      }
      s.remove_suffix(1);
    }
    return std::string(s);
  }
  /// A sequence's length, each item at least `item_bytes`: never more than the bytes left hold.
  std::uint32_t count(std::string_view what, std::size_t item_bytes) {
    const std::uint32_t n = scalar<std::uint32_t>(what);
    if (static_cast<std::uint64_t>(n) * item_bytes > data_.size() - pos_) {
      throw FormatError(cat(what, ": ", n, " items, more than the ", data_.size() - pos_,
                            " bytes left can hold"));
    }
    return n;
  }
  std::string_view bytes(std::size_t n, std::string_view what) {
    need(n, what);
    const std::string_view out = data_.substr(pos_, n);
    pos_ += n;
    return out;
  }

 private:
  void align(std::size_t n) {
    if (cdr_) pos_ = std::min(data_.size(), (pos_ + n - 1) / n * n);
  }
  void need(std::size_t n, std::string_view what) {
    if (n > data_.size() - pos_) {
      throw FormatError(cat(what, " runs past the message's end (", n, " bytes at byte ", pos_,
                            " of ", data_.size(), ")"));
    }
  }

  std::string_view data_;
  std::size_t pos_ = 0;
  bool cdr_ = false;
  bool swap_ = false;
};

/// A PointField's place and type.
struct Field {
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;  ///< 7: FLOAT32, 8: FLOAT64
  bool found = false;
};

double read_float(const char* p, std::uint8_t datatype, bool big_endian) {
  const ScalarType type{'F', datatype == 7 ? 4 : 8};
  return decode_scalar(p, type, big_endian);
}

}  // namespace

RosDepthImage decode_depth_image(std::string_view message, RosEncoding encoding) {
  Wire wire(message, encoding);
  RosDepthImage out;
  out.header = wire.header();
  const std::uint32_t height = wire.scalar<std::uint32_t>("height");
  const std::uint32_t width = wire.scalar<std::uint32_t>("width");
  const std::string type = wire.string("encoding");
  const bool big_endian = wire.scalar<std::uint8_t>("is_bigendian") != 0;
  const std::uint32_t step = wire.scalar<std::uint32_t>("step");
  const std::string_view data = wire.bytes(wire.count("data", 1), "data");
  if (type != "16UC1" && type != "mono16") {
    throw FormatError(
        cat("image encoding '", printable(type, 20), "' is not a depth image's 16UC1 or mono16"));
  }
  if (std::uint64_t{width} * height > kMaxDepthImagePixels) {
    throw FormatError(cat("the image is ", width, " x ", height, " pixels, more than the ",
                          kMaxDepthImagePixels, " a depth image may have"));
  }
  if (std::uint64_t{width} * 2 > step || std::uint64_t{step} * height > data.size()) {
    throw FormatError(cat("step ", step, " and height ", height, " do not fit ", width,
                          " 16-bit pixels a row in ", data.size(), " bytes"));
  }
  out.image.width = static_cast<int>(width);
  out.image.height = static_cast<int>(height);
  out.image.depth.resize(std::size_t{width} * height);
  for (std::uint32_t v = 0; v < height; ++v) {
    for (std::uint32_t u = 0; u < width; ++u) {
      const auto* p = reinterpret_cast<const unsigned char*>(data.data() + std::size_t{v} * step +
                                                             std::size_t{u} * 2);
      out.image.depth[std::size_t{v} * width + u] =
          static_cast<std::uint16_t>(big_endian ? (p[0] << 8) | p[1] : (p[1] << 8) | p[0]);
    }
  }
  return out;
}

RosCameraInfo decode_camera_info(std::string_view message, RosEncoding encoding) {
  Wire wire(message, encoding);
  RosCameraInfo out;
  out.header = wire.header();
  out.intrinsics.height = static_cast<int>(wire.scalar<std::uint32_t>("height") & 0x7fffffff);
  out.intrinsics.width = static_cast<int>(wire.scalar<std::uint32_t>("width") & 0x7fffffff);
  wire.string("distortion_model");
  const std::uint32_t d = wire.count("d", 8);
  for (std::uint32_t i = 0; i < d; ++i) wire.scalar<double>("d");
  std::array<double, 9> k{};
  for (double& x : k) x = wire.scalar<double>("k");
  out.intrinsics.fx = k[0];
  out.intrinsics.cx = k[2];
  out.intrinsics.fy = k[4];
  out.intrinsics.cy = k[5];
  try {
    out.intrinsics.validate();
  } catch (const std::invalid_argument& e) {
    throw FormatError(cat("camera info: ", e.what()));
  }
  return out;
}

RosCloud decode_point_cloud2(std::string_view message, RosEncoding encoding) {
  Wire wire(message, encoding);
  RosCloud cloud;
  cloud.header = wire.header();
  const std::uint32_t height = wire.scalar<std::uint32_t>("height");
  const std::uint32_t width = wire.scalar<std::uint32_t>("width");
  std::array<Field, 3> xyz;
  const std::uint32_t fields = wire.count("fields", 13);
  for (std::uint32_t i = 0; i < fields; ++i) {
    const std::string name = wire.string("fields.name");
    Field f;
    f.offset = wire.scalar<std::uint32_t>("fields.offset");
    f.datatype = wire.scalar<std::uint8_t>("fields.datatype");
    wire.scalar<std::uint32_t>("fields.count");
    f.found = true;
    if (name.size() == 1 && name[0] >= 'x' && name[0] <= 'z') xyz[name[0] - 'x'] = f;
  }
  const bool big_endian = wire.scalar<std::uint8_t>("is_bigendian") != 0;
  const std::uint32_t point_step = wire.scalar<std::uint32_t>("point_step");
  const std::uint32_t row_step = wire.scalar<std::uint32_t>("row_step");
  const std::uint32_t size = wire.count("data", 1);
  const std::string_view data = wire.bytes(size, "data");
  for (int a = 0; a < 3; ++a) {
    const char axis = static_cast<char>('x' + a);
    if (!xyz[a].found) throw FormatError(cat("no field '", axis, "'"));
    if (xyz[a].datatype != 7 && xyz[a].datatype != 8) {
      throw FormatError(cat("field '", axis, "' has datatype ", int{xyz[a].datatype},
                            ", not FLOAT32 (7) or FLOAT64 (8)"));
    }
    const std::uint64_t end = std::uint64_t{xyz[a].offset} + (xyz[a].datatype == 7 ? 4 : 8);
    if (end > point_step) {
      throw FormatError(
          cat("field '", axis, "' ends at byte ", end, ", past point_step ", point_step));
    }
  }
  if (std::uint64_t{width} * point_step > row_step) {
    throw FormatError(cat("row_step ", row_step, " is less than width x point_step (", width, " x ",
                          point_step, ")"));
  }
  if (std::uint64_t{row_step} * height > data.size()) {
    throw FormatError(cat("data holds ", data.size(), " bytes, less than row_step x height (",
                          row_step, " x ", height, ")"));
  }
  cloud.points.reserve(static_cast<std::size_t>(width) * height);
  for (std::uint32_t r = 0; r < height; ++r) {
    for (std::uint32_t c = 0; c < width; ++c) {
      const char* point = data.data() + std::size_t{r} * row_step + std::size_t{c} * point_step;
      Eigen::Vector3d p;
      for (int a = 0; a < 3; ++a)
        p[a] = read_float(point + xyz[a].offset, xyz[a].datatype, big_endian);
      if (p.allFinite()) {
        cloud.points.push_back(p);
      } else {
        ++cloud.non_finite;
      }
    }
  }
  return cloud;
}

std::vector<RosTransform> decode_tf_message(std::string_view message, RosEncoding encoding) {
  Wire wire(message, encoding);
  std::vector<RosTransform> out;
  // NOTE: a transform is at least its stamp, two strings' lengths and 7 doubles.
  const std::uint32_t n = wire.count("transforms", 8 + 8 + 56);
  for (std::uint32_t i = 0; i < n; ++i) {
    RosTransform t;
    t.header = wire.header();
    t.child = wire.string("child_frame_id");
    std::array<double, 7> v{};
    for (double& x : v) x = wire.scalar<double>("transform");
    const Eigen::Vector3d translation(v[0], v[1], v[2]);
    Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
    if (!translation.allFinite() || !q.coeffs().allFinite()) {
      throw FormatError(cat("transform ", i, " (", printable(t.child, 40), ") is not finite"));
    }
    if (std::abs(q.norm() - 1.0) > 1e-3) {
      throw FormatError(cat("transform ", i, " (", printable(t.child, 40),
                            "): rotation quaternion norm ", q.norm(), " is not 1"));
    }
    t.T_parent_child.linear() = q.normalized().toRotationMatrix();
    t.T_parent_child.translation() = translation;
    out.push_back(std::move(t));
  }
  return out;
}

}  // namespace vantage
