#pragma once
/// @file
/// OctoMap's key lattice as the reader and the writer of octomap_io.hpp share it: the headers,
/// the fixed depth, where a grid's cells fall among OctoMap's keys. Included by their .cpp files
/// only.

#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "vantage/map/grid_spec.hpp"
#include "vantage/util/text.hpp"

namespace vantage::detail {

constexpr std::string_view kBinaryHeader = "# Octomap OcTree binary file";
constexpr std::string_view kFullHeader = "# Octomap OcTree file";
constexpr int kTreeDepth = 16;                 // OctoMap's fixed depth
constexpr std::int64_t kKeyCenter = 32768;     // key of the voxel whose min corner is 0
constexpr std::int64_t kKeyCount = 65536;      // keys per axis
constexpr double kAlignmentTolerance = 1e-6;   // [cells]
constexpr double kResolutionTolerance = 1e-5;  // relative; OctoMap prints 6 digits
// A map's resolution [m]: finer than a micrometre or coarser than 10 m is a corrupt header.
constexpr double kMinResolution = 1e-6;
constexpr double kMaxResolution = 10.0;

/// An OctoMap voxel index per axis.
using Voxel = std::array<std::int64_t, 3>;

// Per axis, the OctoMap voxel index (key - 32768) of cell 0: the voxel holding the cell's
// centre, ties going to the upper voxel.
inline Voxel voxel_offset(const GridSpec& spec) {
  Voxel n{};
  for (int a = 0; a < 3; ++a) {
    const double o = spec.origin[a] / spec.resolution;
    n[static_cast<std::size_t>(a)] =
        static_cast<std::int64_t>(std::floor(o + 0.5 + kAlignmentTolerance));
  }
  return n;
}

inline void require_key_range(const GridSpec& spec, const Voxel& n, const std::string& where) {
  static_assert(kKeyCount == 2 * kKeyCenter);
  for (int a = 0; a < 3; ++a) {
    const std::int64_t lo = n[static_cast<std::size_t>(a)] + kKeyCenter;
    const std::int64_t hi = lo + spec.dims[a] - 1;
    if (lo < 0 || hi >= kKeyCount) {
      throw std::invalid_argument(cat(where, ": the grid's cells ", "xyz"[a], " = [",
                                      lo - kKeyCenter, ", ", hi - kKeyCenter,
                                      "] voxels lie outside OctoMap's key range [-32768, 32767]"));
    }
  }
}

}  // namespace vantage::detail
