#pragma once
/// @file
/// Surface normals of a point cloud (PCA of each point's neighbourhood, via PCL).

#include <Eigen/Core>
#include <vector>

#include "vantage/map/point_cloud.hpp"

namespace vantage::perception {

/// How each point's neighbourhood is chosen for its normal.
struct NormalConfig {
  int k_neighbours = 0;  ///< the k nearest points; 0 = every point within `radius`
  double radius = 0.02;  ///< [m] neighbourhood radius when k_neighbours is 0
  int num_threads = 0;   ///< 0 = all cores; each normal is computed alone, so results are
                         ///< identical for any count

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// A unit normal per point, oriented toward `viewpoint` [m], or the zero vector where the
/// neighbourhood has fewer than three points or is degenerate. Throws std::invalid_argument
/// naming the field of a bad config or the first non-finite point.
std::vector<Eigen::Vector3d> estimate_normals(const PointCloud& points, const NormalConfig& config,
                                              const Eigen::Vector3d& viewpoint);

}  // namespace vantage::perception
