#pragma once
/// @file
/// The hand-countable grid of the gain tests: one row of 20 cells along x, the sensor looking
/// along it.

#include <Eigen/Geometry>

#include "vantage/map/occupancy_grid.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage::test {

/// A single row of 20 cells along x, 0.1 m each.
inline GridSpec row_spec() {
  GridSpec spec;
  spec.origin = {0.0, -0.05, -0.05};
  spec.resolution = 0.1;
  spec.dims = {20, 1, 1};
  return spec;
}

/// A 60 x 60 degree view from `origin` along +x, range 0-10 m.
inline Frustum looking_along_x(const Eigen::Vector3d& origin) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = origin;
  return Frustum(pose, SensorFov{deg2rad(60), deg2rad(60), 0.0, 10.0});
}

/// Cells 0-4 free (seen often: p_min), 5-7 unobserved, 8 occupied (p_max), 9-11 unobserved,
/// 12-19 free.
inline OccupancyGrid row_grid() {
  OccupancyGrid grid(row_spec());
  for (std::size_t i = 0; i < 20; ++i) {
    if (i == 8) {
      grid.set_probability(i, grid.params().p_max);
    } else if (i < 5 || i > 11) {
      grid.set_probability(i, grid.params().p_min);
    }
  }
  return grid;
}

}  // namespace vantage::test
