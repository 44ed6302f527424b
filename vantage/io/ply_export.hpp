#pragma once
/// @file
/// The grid's occupied and unobserved cells as a coloured point cloud (PLY) for MeshLab and
/// CloudCompare.

#include <cstddef>
#include <filesystem>

#include "vantage/map/occupancy_grid.hpp"

namespace vantage {

/// Which cells go into the PLY file, and how it is encoded.
struct CellPlyConfig {
  bool occupied = true;    ///< occupied cells, red (255, 0, 0)
  bool unobserved = true;  ///< unobserved cells, yellow (255, 255, 0)
  bool binary = true;      ///< binary little-endian PLY; false writes ASCII
};

/// What an export wrote.
struct CellPlyExport {
  std::size_t occupied = 0;    ///< vertices written for occupied cells
  std::size_t unobserved = 0;  ///< vertices written for unobserved cells
};

/// Writes one vertex per selected cell, at the cell's centre, in linear index order, atomically.
/// Vertex properties: `float x, y, z` [m], `uchar red, green, blue`, and `float probability`
/// (the cell's occupancy, a scalar field in CloudCompare). Throws std::runtime_error naming the
/// path when writing fails.
CellPlyExport write_cells_ply(const std::filesystem::path& path, const OccupancyGrid& grid,
                              const CellPlyConfig& config = {});

}  // namespace vantage
