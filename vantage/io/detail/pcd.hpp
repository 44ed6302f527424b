#pragma once
/// @file
/// The PCD format (v0.7) of the Point Cloud Library, for cloud_io.cpp.

#include <cstddef>
#include <string>
#include <string_view>

#include "vantage/map/point_cloud.hpp"

namespace vantage::detail {

/// The x, y, z of every point of PCD bytes (DATA ascii, binary or binary_compressed; any other
/// fields skipped). Throws FormatError with one line saying what and where.
PointCloud parse_pcd(std::string_view bytes);

/// The header of a binary PCD file of `points` float32 x, y, z points, DATA line included.
std::string pcd_header(std::size_t points);

}  // namespace vantage::detail
