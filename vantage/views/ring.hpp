#pragma once
/// @file
/// Candidate views on a circle around a region of interest (§5.1; docs/model.md "table-top
/// candidates").

#include <Eigen/Geometry>
#include <vector>

#include "vantage/views/frustum.hpp"

namespace vantage {

/// K sensor positions on a horizontal circle, each looking at the circle's centre, times yaw
/// offsets. The paper uses K = 10 and offsets {-15°, 0°, 15°}.
struct RingConfig {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< point every view looks at [m]
  double radius = 1.0;                               ///< horizontal distance to center [m]
  double height = 1.0;                               ///< sensor height (world z) [m]
  int positions = 10;                                ///< K
  double start_angle = 0.0;                          ///< bearing of position 0 around center [rad]
  std::vector<double> yaw_offsets = {deg2rad(-15.0), 0.0, deg2rad(15.0)};  ///< [rad]

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// The ring `vantage plan` puts around a region of interest when not told otherwise: centred on
/// it, a radius of 1.5 half-diagonals of its footprint (at least 1 m), 0.3 m above its top, 10
/// positions, the paper's yaw offsets.
RingConfig default_ring(const Eigen::AlignedBox3d& roi);

/// Pose of a sensor at `eye` looking at `target`, with the sensor's z axis as close to world +z
/// as the direction allows (sensor frame: x forward, y left, z up).
Eigen::Isometry3d look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target);

/// The ring's poses; view (k, j) of position k and offset j has index k * offsets + j.
std::vector<Eigen::Isometry3d> ring_poses(const RingConfig& config);

/// One frustum per pose, all with the same field of view.
std::vector<Frustum> make_views(const std::vector<Eigen::Isometry3d>& poses, const SensorFov& fov);

}  // namespace vantage
