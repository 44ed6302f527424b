#pragma once
/// @file
/// Integration of one scan into the occupancy grid (§4.3; docs/model.md "After a real scan").

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "vantage/map/hole_filling.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/map/point_cloud.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// How a scan updates the grid.
enum class IntegrationMode {
  /// The paper's: hits, MRF/ICM hole filling, then unknown-space estimation — a ray to every
  /// unobserved cell in the scan's frustum, and a miss where nothing occupied lies before it.
  kPaper,
  /// OctoMap's: a miss on every cell a point's ray crosses before its endpoint, a hit on the
  /// endpoint's cell; each cell updated once per scan, a hit winning over a miss.
  kEndpoint,
};

std::string_view to_string(IntegrationMode mode);
/// Parses "paper" or "endpoint"; throws std::invalid_argument naming the value.
IntegrationMode parse_integration_mode(std::string_view name);

/// Settings of scan integration.
struct IntegrationConfig {
  IntegrationMode mode = IntegrationMode::kPaper;
  HoleFillingConfig hole_filling;  ///< used in paper mode
  int num_threads = 0;             ///< 0 = all cores; results are identical for any count

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// One scan in the world frame: the points and the frustum of the sensor that took them.
struct Scan {
  PointCloud points_world;  ///< [m]
  Frustum view;             ///< sensor pose and field of view
};

/// What one integration changed.
struct IntegrationResult {
  std::vector<std::uint32_t> left_unobserved;     ///< cells that left U: the actual gain
  std::vector<std::uint32_t> entered_unobserved;  ///< cells a miss or hit moved back into U
  std::size_t points_inside = 0;                  ///< points that fell in the grid
  std::size_t points_outside = 0;  ///< points outside the grid (their rays still count)
  std::size_t hit_cells = 0;       ///< distinct cells that got a hit
  std::size_t filled_cells = 0;    ///< cells hole filling turned occupied
  std::size_t missed_cells = 0;    ///< distinct cells that got a miss
};

/// Integrates a scan. Throws std::invalid_argument naming the first non-finite point, and leaves
/// the grid untouched in that case.
IntegrationResult integrate_scan(OccupancyGrid& grid, const Scan& scan,
                                 const IntegrationConfig& config);

}  // namespace vantage
