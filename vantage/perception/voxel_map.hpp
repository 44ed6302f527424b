#pragma once
/// @file
/// The reference of scan-to-map registration: one point per voxel of everything registered so
/// far (the centroid of the voxel's points) with a surface normal, kept incrementally. Its size
/// is bounded by the surface area mapped, not by the number of scans.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

#include "vantage/map/point_cloud.hpp"

namespace vantage::perception {

/// Settings of the reference map.
struct VoxelMapConfig {
  double voxel_size = 0.005;   ///< [m] one reference point per voxel of this edge
  int normal_neighbours = 30;  ///< reference points per normal (PCA of the neighbourhood)
  int num_threads = 0;         ///< 0 = all cores; the map is the same for any count

  /// Throws std::invalid_argument naming the field (e.g. "map.voxel_size").
  void validate() const;
};

/// A reference point paired with a query point.
struct MapMatch {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< [m]
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit, toward where it was seen from
  double squared_distance = 0.0;                     ///< [m²] from the query
};

/// Voxel centroids with normals and a k-d tree over them (nanoflann).
class VoxelMap {
 public:
  /// Validates the config; throws std::invalid_argument naming the field.
  explicit VoxelMap(const VoxelMapConfig& config = {});
  ~VoxelMap();
  VoxelMap(VoxelMap&&) noexcept;
  VoxelMap& operator=(VoxelMap&&) noexcept;

  /// Adds world-frame points seen from `viewpoint`: each voxel's centroid moves to the mean of
  /// all its points, the normals of the voxels touched are estimated again and turned toward
  /// `viewpoint` (a surface faces whoever saw it). Deterministic for a given order of adds.
  void add(const PointCloud& points_world, const Eigen::Vector3d& viewpoint);

  /// The nearest reference point with a normal within `max_distance` of `query`, if any.
  std::optional<MapMatch> nearest(const Eigen::Vector3d& query, double max_distance) const;

  std::size_t size() const { return centroids_.size(); }
  bool empty() const { return centroids_.empty(); }
  const PointCloud& points() const { return centroids_; }
  /// Unit normals, or zero where a neighbourhood was degenerate.
  const std::vector<Eigen::Vector3d>& normals() const { return normals_; }
  const VoxelMapConfig& config() const { return config_; }

 private:
  struct Index;  // the k-d tree
  VoxelMapConfig config_;
  std::unordered_map<std::uint64_t, std::uint32_t> slot_of_;  ///< voxel key -> slot
  std::vector<Eigen::Vector3d> sums_;
  std::vector<std::uint32_t> counts_;
  PointCloud centroids_;
  std::vector<Eigen::Vector3d> normals_;
  std::unique_ptr<Index> index_;
};

}  // namespace vantage::perception
