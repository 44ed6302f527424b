#pragma once
/// @file
/// From scans to the map, as the paper's §4.1 chains it: register each new scan to the cloud so
/// far with ICP (§4.2), keep the objects above the table (§5.1), and integrate them into the
/// occupancy grid (§4.3, §4.4). `vantage explore` and `vantage plan` both map through this.

#include <Eigen/Geometry>
#include <cstddef>

#include "vantage/map/integrate.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/map/point_cloud.hpp"
#include "vantage/perception/registration.hpp"
#include "vantage/perception/table_segmentation.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// Settings of the mapping pipeline.
struct MapperConfig {
  OccupancyParams occupancy;
  IntegrationConfig integration;
  bool register_scans = true;  ///< ICP each scan after the first against the cloud so far
  perception::IcpConfig icp;
  bool segment_table = false;  ///< integrate only the points above the table
  perception::TableConfig table;

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// What adding one scan did.
struct MapperUpdate {
  Eigen::Isometry3d T_world_sensor_guess = Eigen::Isometry3d::Identity();  ///< as given
  Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();        ///< used for integration
  bool registered = false;        ///< ICP ran (and converged) for this scan
  double icp_fitness = 0.0;       ///< ICP's mean squared correspondence distance [m^2]
  std::size_t points = 0;         ///< points in the scan
  std::size_t object_points = 0;  ///< points integrated (after table segmentation)
  IntegrationResult integration;
  double seconds_register = 0.0;
  double seconds_segment = 0.0;
  double seconds_integrate = 0.0;
};

/// Builds the map scan by scan. The first scan's pose defines the map frame as given; every later
/// one is corrected by ICP against all registered points so far (when enabled).
class Mapper {
 public:
  /// Validates both; throws std::invalid_argument naming the field.
  Mapper(const GridSpec& grid, const MapperConfig& config);
  /// Continues an existing map (e.g. one read from OctoMap); its own occupancy parameters stay.
  Mapper(OccupancyGrid grid, const MapperConfig& config);

  /// Registers, segments and integrates one scan of points in the sensor frame, taken from the
  /// believed pose `T_world_sensor_guess` with field of view `fov`. Throws std::invalid_argument
  /// for a non-finite point or pose; the map is unchanged then.
  MapperUpdate add_scan(const PointCloud& points_sensor,
                        const Eigen::Isometry3d& T_world_sensor_guess, const SensorFov& fov);

  const OccupancyGrid& grid() const { return grid_; }
  const MapperConfig& config() const { return config_; }
  /// All registered points so far (world frame), the reference of the next registration.
  const PointCloud& registered_cloud() const { return registered_; }
  /// The registered points that went into the grid (world frame): the objects.
  const PointCloud& object_cloud() const { return objects_; }
  std::size_t scans() const { return scans_; }

 private:
  MapperConfig config_;
  OccupancyGrid grid_;
  PointCloud registered_;
  PointCloud objects_;
  std::size_t scans_ = 0;
};

}  // namespace vantage
