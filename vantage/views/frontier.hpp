#pragma once
/// @file
/// Frontier regions (§5.2, after Yamauchi [17]): free cells next to unobserved cells, clustered
/// into connected regions whose centroids become candidate stops.

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <vector>

#include "vantage/map/occupancy_grid.hpp"

namespace vantage {

/// Settings of frontier extraction.
struct FrontierConfig {
  /// Only cells whose centre lies in [min_z, max_z] are frontier cells: the height band the
  /// sensor looks into [m].
  double min_z = -std::numeric_limits<double>::infinity();
  double max_z = std::numeric_limits<double>::infinity();  ///< [m]
  int min_cells = 20;  ///< regions with fewer cells are dropped (noise, slivers)
  /// A region grows from its seed cell only to cells whose centres lie within this distance of
  /// the seed's, so a long frontier (a ring at the sensor's range around an open room, whose
  /// centroid would be the robot itself) splits into pieces whose centroids lie on it. 0 = no
  /// limit: plain connected components [m].
  double max_radius = 1.5;

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// One frontier region.
struct FrontierRegion {
  std::vector<std::uint32_t> cells;  ///< linear indices, the seed (the lowest) first
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< mean of the cells' centres [m]
};

/// Whether cell `linear` is a frontier cell: free, inside the band, and with at least one of its
/// 6 neighbours inside the grid unobserved.
bool is_frontier_cell(const OccupancyGrid& grid, std::size_t linear, const FrontierConfig& config);

/// Every frontier cell, ascending.
std::vector<std::uint32_t> frontier_cells(const OccupancyGrid& grid, const FrontierConfig& config);

/// Frontier cells clustered into regions: 26-connected, grown breadth-first from the lowest
/// unassigned cell (within `max_radius` of it), regions below `min_cells` dropped. Ordered by
/// their seed cell, so the result is deterministic.
std::vector<FrontierRegion> frontier_regions(const OccupancyGrid& grid,
                                             const FrontierConfig& config);

}  // namespace vantage
