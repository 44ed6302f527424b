#pragma once
/// @file
/// Voxel-grid downsampling of a point cloud, without PCL.

#include <cstddef>
#include <vector>

#include "vantage/map/point_cloud.hpp"

namespace vantage::perception {

/// One point per occupied voxel of edge `voxel_size` [m] (a lattice with a corner at the origin):
/// the centroid of the voxel's points, in ascending (z, y, x) voxel order. A `voxel_size` of 0
/// returns the input unchanged. Unlike PCL's VoxelGrid it never overflows: any extent works.
///
/// When `counts` is given, it is set to how many input points each output point stands for.
///
/// Throws std::invalid_argument for a negative or non-finite `voxel_size` or a non-finite point
/// (naming its index).
PointCloud voxel_downsample(const PointCloud& points, double voxel_size,
                            std::vector<std::size_t>* counts = nullptr);

}  // namespace vantage::perception
