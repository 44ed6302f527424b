#pragma once
/// @file
/// Depth images in (issue 38): a 16-bit PNG, as depth cameras and the public RGB-D data sets give
/// them (TUM RGB-D: 5000 units a metre; ROS's 16UC1 and OpenNI: millimetres), turned into one ray
/// end per pixel in the camera's optical frame.

#include <cstdint>
#include <filesystem>
#include <string_view>
#include <vector>

#include "vantage/io/manifest.hpp"
#include "vantage/map/integrate.hpp"
#include "vantage/map/point_cloud.hpp"

namespace vantage {

/// A depth image: per pixel the depth along the optical axis (z, not the range along the ray) in
/// raw units, row by row from the top left.
struct DepthImage {
  int width = 0;   ///< [px]
  int height = 0;  ///< [px]
  std::vector<std::uint16_t> depth;
};

/// Decodes a 16-bit greyscale PNG (any bit of interlacing or chunk order libpng reads). Throws
/// FormatError with one line saying what is wrong: not a PNG, another bit depth or colour type
/// (named), more than kMaxDepthImagePixels, or what libpng found (a bad CRC, a truncated stream).
/// The pixel count is checked against the limit and the memory available before allocation.
DepthImage decode_depth_png(std::string_view bytes);

/// Reads `path` (a regular file of at most kMaxDepthImageFileBytes) and decodes it. Throws
/// std::runtime_error "path: what".
DepthImage read_depth_png(const std::filesystem::path& path);

/// The image as integration reads it (map/integrate.hpp: integrate_depth, each valid pixel one
/// ray, no point cloud in between), a view of `image`'s depths, which must outlive it. Throws
/// std::invalid_argument for bad intrinsics or encoding, or when the image's size is not the
/// intrinsics'.
DepthFrame depth_frame(const DepthImage& image, const PinholeIntrinsics& intrinsics,
                       const DepthEncoding& encoding);

/// The ray end of every valid pixel, in the camera's optical frame (z forward, x right, y down)
/// [m], by DepthFrame::optical_point: pixel (u, v) of depth z ends at ((u - cx) z / fx,
/// (v - cy) z / fy, z), each coordinate rounded to float. One point per pixel, in row order; a
/// pixel of `encoding.invalid` gives none. Throws as depth_frame.
PointCloud depth_to_points(const DepthImage& image, const PinholeIntrinsics& intrinsics,
                           const DepthEncoding& encoding);

}  // namespace vantage
