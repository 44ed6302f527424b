#pragma once
/// @file
/// Point clouds on disk: PCD (v0.7) and PLY, chosen by the file's extension.

#include <Eigen/Geometry>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "vantage/map/point_cloud.hpp"

namespace vantage {

/// How read_point_cloud treats points with a non-finite coordinate.
struct CloudReadOptions {
  /// Drop them instead of failing: organized RGB-D clouds mark pixels without depth with NaN.
  bool skip_non_finite = false;
};

/// What reading a cloud found besides its points.
struct CloudReadStats {
  std::size_t non_finite_skipped = 0;  ///< points dropped by CloudReadOptions::skip_non_finite
};

/// A cloud holds a point with a non-finite coordinate (and skip_non_finite is off).
struct NonFinitePointError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Reads the x, y, z of every point of a `.pcd` (DATA ascii, binary or binary_compressed) or
/// `.ply` (ascii, binary_little_endian or binary_big_endian; the `vertex` element) file [m].
/// Other fields and elements are ignored; the extension is matched without regard to case.
///
/// Throws std::invalid_argument for any other extension, and std::runtime_error with one line
/// that names the file when it cannot be read, is malformed (with the line or point where),
/// holds no point, or holds a non-finite coordinate (NonFinitePointError, with the point's index;
/// unless `options.skip_non_finite`, and then only when no finite point is left). Nothing partial
/// is ever returned. `stats`, when given, receives what was skipped.
PointCloud read_point_cloud(const std::filesystem::path& path, const CloudReadOptions& options = {},
                            CloudReadStats* stats = nullptr);

/// The acquisition pose a `.pcd` file's VIEWPOINT field records (tx ty tz qw qx qy qz), the way
/// PCL's `sensor_origin_` and `sensor_orientation_` and strands' nbv_planning use it: the sensor's
/// pose in the frame of the cloud's poses, T_world_cloud, while the points are in the sensor's
/// frame. Nothing for a `.ply` file, a header without VIEWPOINT, and the poses PCD writers put
/// there when nobody set one (a pose nobody set is no pose): the identity, and the half turn
/// about x at the origin (`0 0 0 0 1 0 0`, as PCL's own stereo test frame carries). Reads the
/// header only.
///
/// Throws std::invalid_argument for another extension, and std::runtime_error naming the file
/// when it cannot be read or its header is malformed (a VIEWPOINT that is not 7 numbers, or
/// whose quaternion is not of unit length).
std::optional<Eigen::Isometry3d> read_cloud_viewpoint(const std::filesystem::path& path);

/// Writes `points` as binary PCD (`.pcd`) or binary little-endian PLY (`.ply`) with float32
/// x, y, z, the layout PCL's `pcl::PointXYZ` readers and viewers expect. Coordinates are
/// rounded to float (about 0.1 µm at 1 m). A PCD file records `viewpoint`, when given, as its
/// VIEWPOINT (to the last digit); PLY has no such field. The file is written atomically: whole or
/// not at all.
///
/// Throws std::invalid_argument naming the file for another extension, an empty cloud, or a
/// point that is not finite in float (naming the point's index), before anything is written;
/// std::runtime_error naming the file when writing fails.
/// Throws std::invalid_argument naming the path unless its extension is .pcd or .ply (any case):
/// what write_point_cloud checks, for a command line to decide before any work.
void require_point_cloud_extension(const std::filesystem::path& path);

void write_point_cloud(const std::filesystem::path& path, const PointCloud& points,
                       const std::optional<Eigen::Isometry3d>& viewpoint = std::nullopt);

}  // namespace vantage
