#pragma once
/// @file
/// The point-cloud value that crosses Vantage's API: a vector of Eigen points.

#include <Eigen/Geometry>
#include <vector>

namespace vantage {

/// Points in one frame, named by the variable (points_world, points_sensor) [m].
using PointCloud = std::vector<Eigen::Vector3d>;

/// Applies T_a_b to points in frame b, giving points in frame a.
inline PointCloud transform(const Eigen::Isometry3d& T_a_b, const PointCloud& points_b) {
  PointCloud points_a;
  points_a.reserve(points_b.size());
  for (const Eigen::Vector3d& p : points_b) points_a.push_back(T_a_b * p);
  return points_a;
}

}  // namespace vantage
