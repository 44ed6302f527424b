#include "vantage/perception/voxel_filter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "vantage/util/text.hpp"

namespace vantage::perception {

PointCloud voxel_downsample(const PointCloud& points, double voxel_size) {
  if (!(voxel_size >= 0.0 && std::isfinite(voxel_size))) {
    throw std::invalid_argument(cat("voxel_size must be >= 0 and finite, got ", voxel_size));
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw std::invalid_argument(cat("voxel_downsample: point ", i, " is not finite"));
    }
  }
  if (voxel_size == 0.0) return points;

  using Key = Eigen::Matrix<std::int64_t, 3, 1>;
  std::vector<Key> keys(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      // NOTE: clamped so that absurd coordinates cannot overflow the conversion.
      const double cell = std::clamp(std::floor(points[i][a] / voxel_size), -4e18, 4e18);
      keys[i][a] = static_cast<std::int64_t>(cell);
    }
  }
  const auto less = [&keys](std::size_t a, std::size_t b) {
    const Key& ka = keys[a];
    const Key& kb = keys[b];
    if (ka.z() != kb.z()) return ka.z() < kb.z();
    if (ka.y() != kb.y()) return ka.y() < kb.y();
    if (ka.x() != kb.x()) return ka.x() < kb.x();
    return a < b;  // the sum below then runs in input order within a voxel
  };
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), less);

  PointCloud out;
  for (std::size_t begin = 0; begin < order.size();) {
    std::size_t end = begin;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    while (end < order.size() && keys[order[end]] == keys[order[begin]])
      sum += points[order[end++]];
    out.push_back(sum / static_cast<double>(end - begin));
    begin = end;
  }
  return out;
}

}  // namespace vantage::perception
