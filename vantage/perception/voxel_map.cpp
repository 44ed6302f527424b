#include "vantage/perception/voxel_map.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <nanoflann.hpp>
#include <stdexcept>
#include <utility>

#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage::perception {
namespace {

/// nanoflann's view of the centroids.
struct Points {
  const PointCloud* cloud;
  std::size_t kdtree_get_point_count() const { return cloud->size(); }
  double kdtree_get_pt(std::size_t i, std::size_t d) const { return (*cloud)[i][d]; }
  template <class Box>
  bool kdtree_get_bbox(Box& /*box*/) const {
    return false;
  }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Points>,
                                                 Points, 3, std::uint32_t>;

/// A voxel's key: its integer coordinates, 21 bits each (±10 km at 1 cm).
std::uint64_t voxel_key(const Eigen::Vector3d& p, double voxel_size) {
  std::uint64_t key = 0;
  for (int d = 0; d < 3; ++d) {
    const auto v = static_cast<std::int64_t>(std::floor(p[d] / voxel_size));
    key = (key << 21) | (static_cast<std::uint64_t>(v) & ((std::uint64_t{1} << 21) - 1));
  }
  return key;
}

}  // namespace

struct VoxelMap::Index {
  Points points;
  Tree tree;
  explicit Index(const PointCloud& cloud)
      : points{&cloud}, tree(3, points, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {}
};

void VoxelMapConfig::validate() const {
  if (!(voxel_size > 0.0 && std::isfinite(voxel_size))) {
    throw std::invalid_argument(cat("map.voxel_size must be > 0 m, got ", voxel_size));
  }
  if (normal_neighbours < 3) {
    throw std::invalid_argument(cat("map.normal_neighbours must be >= 3, got ", normal_neighbours));
  }
  if (num_threads < 0) {
    throw std::invalid_argument(cat("map.num_threads must be >= 0, got ", num_threads));
  }
}

VoxelMap::VoxelMap(const VoxelMapConfig& config) : config_(config) { config_.validate(); }
VoxelMap::~VoxelMap() = default;
// NOTE: the tree reads the centroids through a pointer to the member, which a move must follow.
VoxelMap::VoxelMap(VoxelMap&& other) noexcept { *this = std::move(other); }
VoxelMap& VoxelMap::operator=(VoxelMap&& other) noexcept {
  config_ = other.config_;
  slot_of_ = std::move(other.slot_of_);
  sums_ = std::move(other.sums_);
  counts_ = std::move(other.counts_);
  centroids_ = std::move(other.centroids_);
  normals_ = std::move(other.normals_);
  index_ = std::move(other.index_);
  if (index_) index_->points.cloud = &centroids_;
  return *this;
}

void VoxelMap::add(const PointCloud& points_world, const Eigen::Vector3d& viewpoint) {
  if (points_world.empty()) return;
  std::vector<std::uint32_t> touched;
  std::vector<bool> is_touched(centroids_.size(), false);
  for (const Eigen::Vector3d& p : points_world) {
    if (!p.allFinite()) throw std::invalid_argument("voxel map: a point is not finite");
    const auto [it, inserted] = slot_of_.try_emplace(voxel_key(p, config_.voxel_size),
                                                     static_cast<std::uint32_t>(sums_.size()));
    if (inserted) {
      sums_.push_back(Eigen::Vector3d::Zero());
      counts_.push_back(0);
      is_touched.push_back(false);
    }
    const std::uint32_t slot = it->second;
    sums_[slot] += p;
    ++counts_[slot];
    if (!is_touched[slot]) {
      is_touched[slot] = true;
      touched.push_back(slot);
    }
  }
  centroids_.resize(sums_.size());
  normals_.resize(sums_.size(), Eigen::Vector3d::Zero());
  for (const std::uint32_t slot : touched) centroids_[slot] = sums_[slot] / counts_[slot];
  index_ = std::make_unique<Index>(centroids_);

  // NOTE: only the voxels this add touched get a new normal: the others' neighbourhoods changed
  // little, and re-estimating every normal would make the map's cost grow with the run.
  const auto k = static_cast<std::size_t>(config_.normal_neighbours);
  run_with_threads(config_.num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, touched.size(), [&](std::size_t t) {
      const std::uint32_t slot = touched[t];
      std::vector<std::uint32_t> ids(k);
      std::vector<double> squared(k);
      const std::size_t n =
          index_->tree.knnSearch(centroids_[slot].data(), k, ids.data(), squared.data());
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      if (n >= 3) {
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        for (std::size_t i = 0; i < n; ++i) mean += centroids_[ids[i]];
        mean /= static_cast<double>(n);
        Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
        for (std::size_t i = 0; i < n; ++i) {
          const Eigen::Vector3d d = centroids_[ids[i]] - mean;
          covariance += d * d.transpose();
        }
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
        if (eigen.eigenvalues()(1) > 0.0) normal = eigen.eigenvectors().col(0).normalized();
        if (normal.dot(viewpoint - centroids_[slot]) < 0.0) normal = -normal;
      }
      normals_[slot] = normal;
    });
  });
}

std::optional<MapMatch> VoxelMap::nearest(const Eigen::Vector3d& query, double max_distance) const {
  if (!index_) return std::nullopt;
  std::uint32_t id = 0;
  double squared = 0.0;
  if (index_->tree.knnSearch(query.data(), 1, &id, &squared) != 1) return std::nullopt;
  if (squared > max_distance * max_distance || normals_[id].isZero()) return std::nullopt;
  return MapMatch{centroids_[id], normals_[id], squared};
}

}  // namespace vantage::perception
