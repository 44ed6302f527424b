#pragma once
/// @file
/// Table-top segmentation (§5.1): find the table as the dominant horizontal plane and keep the
/// points above it, within its extent. Only these object points go into the grid.

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <numbers>
#include <vector>

#include "vantage/map/point_cloud.hpp"

namespace vantage::perception {

/// Settings of table-top segmentation. Defaults suit a 1 m table scanned at about 1.2 m with a
/// few mm of range noise, mapped at 7.8 mm cells.
struct TableConfig {
  /// [m] the plane search runs on the cloud downsampled to this voxel; the full cloud's points
  /// near the plane found then refit it and give the table's extent, and the objects are taken
  /// from the full cloud. 0 = no downsampling. NOTE: 2 cm, not 5 mm: the search's cost falls
  /// with the sample's size (a Kinect frame: 67 k points at 5 mm, 6 k at 2 cm) and the refit on
  /// the full cloud gives back the plane's precision.
  double voxel_size = 0.02;
  double normal_radius = 0.05;  ///< [m] neighbourhood of each normal when normal_neighbours is 0
  int normal_neighbours = 0;    ///< k nearest neighbours per normal instead of the radius; 0 = off

  double distance_threshold = 0.01;  ///< [m] RANSAC: inliers lie within this of the plane
  /// [rad] a plane's normal, and each inlier's, lies within this angle of world +z.
  double max_angle = 10.0 * std::numbers::pi / 180.0;
  double normal_distance_weight = 0.1;  ///< PCL's weight of the normal's angle in the inlier test
  int max_iterations = 1000;            ///< RANSAC iterations per plane
  std::size_t min_inliers = 50;         ///< fewer (downsampled) inliers end the plane search
  int max_planes = 6;                   ///< horizontal planes to find before taking the largest
  double min_table_z = -std::numeric_limits<double>::infinity();  ///< [m] lowest table height
  double max_table_z = std::numeric_limits<double>::infinity();   ///< [m] highest table height

  double min_height = 0.01;  ///< [m] object points lie more than this above the table plane
  double max_height = 0.5;   ///< [m] ... and at most this (the 65-cell grid is 0.51 m high)
  double margin = 0.01;      ///< [m] the table's extent (convex hull of its inliers) grown by this

  int num_threads = 0;  ///< for the normals; 0 = all cores; results are identical for any count

  /// Throws std::invalid_argument naming the field (e.g. "table.distance_threshold").
  void validate() const;
};

/// What segmentation found.
struct TableSegmentation {
  bool found = false;  ///< a horizontal plane with at least min_inliers points was found
  /// The table plane (a, b, c, d): a·x + b·y + c·z + d = 0 with (a, b, c) the unit normal,
  /// pointing up (c > 0). Zero when not found.
  Eigen::Vector4d plane = Eigen::Vector4d::Zero();
  PointCloud objects;                       ///< input points above the table, within its extent
  std::vector<std::size_t> object_indices;  ///< their indices in the input, ascending
  /// Input points within distance_threshold of the plane and inside its extent.
  std::size_t table_inliers = 0;
  /// The table's extent: convex hull of its inliers (of the sample and of the full cloud)
  /// projected onto the plane, counter-clockwise
  /// seen from above, in the world frame [m]. Without the margin.
  std::vector<Eigen::Vector3d> table_hull;
};

/// Segments a world-frame cloud (z up): on the cloud downsampled to voxel_size, estimates
/// normals, finds horizontal planes one after the other with RANSAC (PCL's
/// SACMODEL_NORMAL_PARALLEL_PLANE about +z) and takes the one with the most inliers (and a height
/// in [min_table_z, max_table_z]) as the table; then refits it by least squares to the full
/// cloud's points within distance_threshold of it and within a voxel of its inliers' extent, and
/// keeps the points above it within the extent of all its inliers. When no table is found,
/// `objects` is empty and `found` false.
///
/// Deterministic: PCL's RANSAC is seeded with its fixed seed (12345) and runs serially, and the
/// normals do not depend on the thread count, so the same input gives the same output.
/// Throws std::invalid_argument for a bad config or a non-finite point (naming its index).
TableSegmentation segment_table(const PointCloud& points_world, const TableConfig& config);

}  // namespace vantage::perception
