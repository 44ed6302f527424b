#pragma once
/// @file
/// A sensor's pose from the table it looks at: a single frame from a depth camera on no robot
/// has no pose, but a table top fixes all that a table-top map needs. The table's plane gives the
/// world's up and the sensor's height above the table; the table frame puts the table's top at a
/// stated height, the world's origin on the table below the objects, and the world's x axis
/// along the sensor's view (the table's far side lies toward +x).

#include <Eigen/Geometry>
#include <cstddef>
#include <numbers>
#include <optional>

#include "vantage/map/point_cloud.hpp"
#include "vantage/perception/table_segmentation.hpp"

namespace vantage::perception {

/// Settings of the pose from the table.
struct TablePoseConfig {
  double table_height = 0.75;  ///< [m] the world z of the table's top
  /// [rad] the table's normal lies within this angle of the sensor's up (+z of its x-forward
  /// frame): a camera looking down at a table pitches down by less than this.
  double max_tilt = 75.0 * std::numbers::pi / 180.0;
  /// The plane search; its max_angle is replaced by max_tilt, its height limits are not used.
  TableConfig table;

  /// Throws std::invalid_argument naming the field (e.g. "table_height").
  void validate() const;
};

/// The pose found, and what it rests on.
struct TablePose {
  /// The sensor's pose in the table frame (x forward, y left, z up sensor axes).
  Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
  double height_above_table = 0.0;  ///< [m] the sensor's height above the table's top
  double tilt = 0.0;                ///< [rad] angle between the sensor's forward axis and level
  std::size_t table_points = 0;     ///< points on the table's plane, within its extent
  std::size_t object_points = 0;    ///< points above the table, within its extent
};

/// Finds the table in a cloud in the sensor's x-forward frame (the largest plane whose normal
/// lies within max_tilt of the sensor's up, below the sensor) and returns the sensor's pose in
/// the table frame: z up along the table's normal, the table's top at table_height, the origin
/// on the table below the centroid of the points above it (the table's centroid when there are
/// none), x along the sensor's forward axis projected onto the table (its up axis when it looks
/// straight down). Nothing when no such plane is found. Deterministic, as segment_table.
/// Throws std::invalid_argument for a bad config or a non-finite point.
std::optional<TablePose> estimate_table_pose(const PointCloud& points_sensor,
                                             const TablePoseConfig& config);

}  // namespace vantage::perception
