#include "vantage/io/cloud_io.hpp"

// NOTE: PCL's readers are not used. PCL 1.13's PCDReader crashes (SIGSEGV) on a file that is not
// a PCD file, and both its PCD and PLY readers turn a non-numeric ASCII value into 0 without a
// word; this module must name the file and never return a partial or invented cloud. Nor is
// pcl_io linked for its LZF decoder: it drags some 60 shared libraries (VTK, Qt) into every
// program that reads a cloud, so binary_compressed PCD data is decoded in pcd.cpp. PLY goes
// through the one PLY reader (ply.hpp), which reads meshes too.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "vantage/io/atomic_file.hpp"
#include "vantage/io/detail/pcd.hpp"
#include "vantage/io/format_parsing.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/io/ply.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {
namespace fs = std::filesystem;

enum class Format { kPcd, kPly };

/// A PCD header is read from at most this many bytes at the file's start.
constexpr std::size_t kHeaderBytes = std::size_t{1} << 16;

Format format_of(const fs::path& path) {
  const std::string extension = lower_extension(path);
  if (extension == ".pcd") return Format::kPcd;
  if (extension == ".ply") return Format::kPly;
  throw std::invalid_argument(cat(path.string(), ": unsupported point-cloud format '", extension,
                                  "' (expected .pcd or .ply)"));
}

/// The x, y, z of every vertex of a PLY file; other elements and properties are not used.
PointCloud parse_ply_cloud(std::string_view bytes) {
  const PlyReader ply(bytes);
  const auto v = ply.find("vertex");
  if (!v) throw FormatError("the PLY file has no vertex element");
  const PlyElement& vertex = ply.elements()[*v];
  std::size_t xyz[3];
  for (int a = 0; a < 3; ++a) {
    const std::string_view name = std::string_view("xyz").substr(static_cast<std::size_t>(a), 1);
    const auto k = vertex.find(name);
    if (!k) throw FormatError(cat("the PLY vertex element has no scalar property '", name, "'"));
    xyz[a] = *k;
  }
  if (vertex.count == 0) throw FormatError("the cloud is empty");
  PointCloud cloud;
  cloud.reserve(vertex.count);  // the reader checked that the data can hold them
  ply.read(*v, [&](std::size_t e, std::uint64_t, const PlyRecord& r) {
    if (e == *v) cloud.emplace_back(r.scalar(xyz[0]), r.scalar(xyz[1]), r.scalar(xyz[2]));
  });
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

/// For a binary PLY file some of whose points are not finite: the byte order in which all of
/// them are, when it is not the one its header names (a big-endian file that says little-endian,
/// or the other way round: issue 53 found it blamed on a NaN); else empty.
std::string_view other_byte_order(const std::string& bytes) {
  static constexpr std::string_view kOrders[] = {"binary_big_endian", "binary_little_endian"};
  const std::size_t end = bytes.find("end_header");
  for (int i = 0; i < 2; ++i) {
    const std::size_t at = bytes.find(cat("format ", kOrders[i], " "));
    if (at == std::string::npos || at > end) continue;
    std::string swapped = bytes;
    swapped.replace(at + 7, kOrders[i].size(), kOrders[1 - i]);
    try {
      const PointCloud cloud = parse_ply_cloud(swapped);
      if (!cloud.empty() && std::all_of(cloud.begin(), cloud.end(),
                                        [](const Eigen::Vector3d& p) { return p.allFinite(); })) {
        return kOrders[1 - i];
      }
    } catch (const FormatError&) {
    }
  }
  return {};
}

}  // namespace

PointCloud read_point_cloud(const fs::path& path, const CloudReadOptions& options,
                            CloudReadStats* stats) {
  const Format format = format_of(path);
  PointCloud cloud;
  std::string bytes;
  try {
    bytes = read_input_file(path, InputKind::kPointCloud);
    // NOTE: an extension that lies is said as such, not as the other format's first complaint
    // (a PLY file named .pcd: "unknown PCD header key 'ply'").
    const std::string_view expected = format == Format::kPcd ? "a PCD point cloud" : "a PLY file";
    if (const std::string_view found = sniff_format(std::string_view(bytes).substr(0, 4096));
        !found.empty() && found != expected) {
      throw FormatError(
          cat("holds ", found, ", not what its ", lower_extension(path), " extension says"));
    }
    cloud = format == Format::kPcd ? detail::parse_pcd(bytes) : parse_ply_cloud(bytes);
    if (options.skip_non_finite) {
      const std::size_t skipped =
          std::erase_if(cloud, [](const Eigen::Vector3d& p) { return !p.allFinite(); });
      if (stats) stats->non_finite_skipped = skipped;
      if (cloud.empty()) throw FormatError("no point has finite coordinates");
    }
  } catch (const FormatError& e) {
    throw std::runtime_error(cat(path.string(), ": ", e.what()));
  }
  try {
    check_finite(cloud);
  } catch (const FormatError& e) {
    if (format == Format::kPly) {
      if (const std::string_view order = other_byte_order(bytes); !order.empty()) {
        throw std::runtime_error(cat(path.string(), ": ", e.what(), "; read as ", order,
                                     " every point is finite: its header names the wrong byte "
                                     "order"));
      }
    }
    throw NonFinitePointError(cat(path.string(), ": ", e.what()));
  }
  return cloud;
}

namespace {

/// Whether a VIEWPOINT is one that writers put there by default: the identity, or the half turn
/// about x at the origin (qw 0, qx 1), both with no translation.
bool is_unset_viewpoint(const Eigen::Isometry3d& pose) {
  Eigen::Isometry3d half_turn = Eigen::Isometry3d::Identity();
  half_turn.linear() = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  return pose.isApprox(Eigen::Isometry3d::Identity(), 1e-12) || pose.isApprox(half_turn, 1e-12);
}

}  // namespace

std::optional<Eigen::Isometry3d> read_cloud_viewpoint(const fs::path& path) {
  if (format_of(path) != Format::kPcd) return std::nullopt;
  try {
    const std::optional<Eigen::Isometry3d> pose =
        detail::parse_pcd_viewpoint(read_input_file(path, InputKind::kPointCloud, kHeaderBytes));
    if (pose && is_unset_viewpoint(*pose)) return std::nullopt;
    return pose;
  } catch (const FormatError& e) {
    throw std::runtime_error(cat(path.string(), ": ", e.what()));
  }
}

void require_point_cloud_extension(const fs::path& path) { (void)format_of(path); }

void write_point_cloud(const fs::path& path, const PointCloud& points,
                       const std::optional<Eigen::Isometry3d>& viewpoint) {
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
      format == Format::kPcd ? detail::pcd_header(points.size(), viewpoint)
                             : ply_header(PlyFormat::kBinaryLittleEndian, {"written by vantage"},
                                          {{"vertex", points.size(), {{"x"}, {"y"}, {"z"}}}});
  write_atomically(path, [&](std::ostream& out) {
    out << header;
    out.write(reinterpret_cast<const char*>(packed.data()),
              static_cast<std::streamsize>(packed.size() * sizeof(float)));
  });
}

}  // namespace vantage
