#pragma once
/// @file
/// Integration of one scan into the occupancy grid (§4.3; docs/model.md "After a real scan").

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <span>
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

/// A depth image as integration reads it (issue 38): per pixel the depth along the optical axis
/// (z, not the range along the ray) in raw units, row by row from the top left, with the pinhole
/// intrinsics of the camera that took it.
struct DepthFrame {
  int width = 0;                         ///< [px]
  int height = 0;                        ///< [px]
  std::span<const std::uint16_t> depth;  ///< width x height raw values
  double fx = 0.0, fy = 0.0;             ///< focal lengths [px]
  double cx = 0.0, cy = 0.0;             ///< principal point [px], pixel centres at integers
  /// [1/m] raw units a metre: 1000 for millimetres (ROS 16UC1, OpenNI), 5000 for TUM RGB-D.
  double units_per_metre = 1000.0;
  std::uint16_t invalid = 0;  ///< the raw value of a pixel without depth (0 for all of those)

  /// Throws std::invalid_argument naming the field: positive finite focal lengths and scale,
  /// width x height values.
  void validate() const;
  /// The ray end of pixel (u, v) of raw depth `d` in the camera's optical frame (z forward,
  /// x right, y down) [m]: ((u - cx) z / fx, (v - cy) z / fy, z) with z = d / units_per_metre,
  /// each coordinate rounded to float, as a PCD file or a PointCloud2 message of the same frame
  /// holds it, so that every way of handing over a frame maps the same.
  Eigen::Vector3d optical_point(int u, int v, std::uint16_t d) const;
};

/// Integrates a depth image directly, each valid pixel one ray from the camera's centre to its
/// ray end (DepthFrame::optical_point), without a point cloud in between. `view` is the sensor's
/// pose (x forward, y left, z up: the optical frame turned so) and field of view. The same grid,
/// cell for cell, as integrate_scan of the valid pixels' points in row order. `mask`, when not
/// empty (width x height), integrates only the pixels where it is non-zero. Throws
/// std::invalid_argument for a bad frame or a mask of another size.
IntegrationResult integrate_depth(OccupancyGrid& grid, const DepthFrame& frame, const Frustum& view,
                                  const IntegrationConfig& config,
                                  std::span<const std::uint8_t> mask = {});

}  // namespace vantage
