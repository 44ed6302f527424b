#pragma once
/// @file
/// The PCD format (v0.7) of the Point Cloud Library, for cloud_io.cpp.

#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "vantage/map/point_cloud.hpp"

namespace vantage::detail {

/// The x, y, z of every point of PCD bytes (DATA ascii, binary or binary_compressed; any other
/// fields skipped). Throws FormatError with one line saying what and where.
PointCloud parse_pcd(std::string_view bytes);

/// The pose a PCD header's VIEWPOINT line records (tx ty tz qw qx qy qz), or nothing when the
/// header has none. `bytes` may end anywhere after the DATA line. Throws FormatError for a
/// malformed header or VIEWPOINT (not 7 numbers, a quaternion far from unit length).
std::optional<Eigen::Isometry3d> parse_pcd_viewpoint(std::string_view bytes);

/// The header of a binary PCD file of `points` float32 x, y, z points, DATA line included, with
/// `viewpoint` as its VIEWPOINT (the identity, PCD's default, when there is none).
std::string pcd_header(std::size_t points, const std::optional<Eigen::Isometry3d>& viewpoint = {});

}  // namespace vantage::detail
