#pragma once
/// @file
/// The map files a results folder holds, written the same way by `vantage explore` and
/// `vantage plan`: the lossless map to continue from, a copy for viewers, and the top view the
/// pictures draw.

#include <filesystem>

#include "vantage/map/occupancy_grid.hpp"

namespace vantage {

/// Writes, each atomically, into `dir`:
/// - `map.ot`: every cell's float log-odds bit for bit (vantage/io/octomap_io.hpp); `vantage plan
///   --map map.ot` continues from exactly this map;
/// - `map.bt`: free and occupied classes only, for OctoMap viewers (octovis);
/// - `map_top.csv`: the top view (write_top_view).
/// Throws what the writers throw, naming the file.
void write_map_files(const std::filesystem::path& dir, const OccupancyGrid& grid);

/// Writes the grid seen from above as CSV, one row per (x, y) column holding an occupied or an
/// unobserved cell: `x,y` (the column's centre [m]), `occupied` and `unobserved` (cells of each
/// class in the column), `top` (centre height of the highest occupied cell [m], empty when none).
/// The header's comment line names the grid (origin, resolution, dims) so that a plot can draw
/// the columns as squares of the right size.
void write_top_view(const std::filesystem::path& path, const OccupancyGrid& grid);

}  // namespace vantage
