#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "vantage/perception/normals.hpp"
#include "vantage/perception/voxel_filter.hpp"

namespace vantage::perception {
namespace {

TEST(VoxelDownsample, AveragesEachVoxelInLatticeOrder) {
  const PointCloud points = {
      {0.05, 0.05, 0.05}, {0.15, 0.05, 0.05},   // voxel (1, 0, 0) with the next
      {0.11, 0.01, 0.09}, {-0.05, 0.0, 0.0},    // voxel (-1, 0, 0)
      {0.05, 0.05, 0.25}, {0.02, 0.08, 0.01}};  // voxel (0, 0, 2); voxel (0, 0, 0) with the first
  const PointCloud out = voxel_downsample(points, 0.1);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_TRUE(out[0].isApprox(Eigen::Vector3d(-0.05, 0.0, 0.0)));
  EXPECT_TRUE(out[1].isApprox(Eigen::Vector3d(0.035, 0.065, 0.03)));
  EXPECT_TRUE(out[2].isApprox(Eigen::Vector3d(0.13, 0.03, 0.07)));
  EXPECT_TRUE(out[3].isApprox(Eigen::Vector3d(0.05, 0.05, 0.25)));
  EXPECT_EQ(voxel_downsample(points, 0.0), points);
  EXPECT_TRUE(voxel_downsample({}, 0.1).empty());
}

TEST(VoxelDownsample, KeepsOnePointPerOccupiedVoxelAtAnyExtent) {
  // PCL's VoxelGrid gives up beyond 2^31 voxels; this must not.
  const PointCloud points = {{-1e4, 0, 0}, {1e4, 0, 0}, {0, 1e4, 1e4}, {1e4 + 1e-4, 0, 0}};
  EXPECT_EQ(voxel_downsample(points, 0.001).size(), 3u);
}

// The oracle: a map from each voxel, in (z, y, x) order, to its points' sum in input order.
// Both of voxel_downsample's sorts are checked: voxels within 2^21 of each other (packed) and a
// cloud with one far point (compared).
TEST(VoxelDownsample, EqualsABruteForceCentroidPerVoxel) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> coord(-0.3, 0.5);
  PointCloud points;
  for (int i = 0; i < 20000; ++i) points.emplace_back(coord(rng), coord(rng), 0.1 * coord(rng));
  for (int i = 0; i < 500; ++i) points.push_back(points[static_cast<std::size_t>(i) * 7]);
  for (const bool far : {false, true}) {
    PointCloud cloud = points;
    if (far) cloud.emplace_back(0.0, 0.0, 1e5);
    for (const double voxel : {0.007, 0.02, 0.1}) {
      std::map<std::tuple<double, double, double>, std::pair<Eigen::Vector3d, std::size_t>> oracle;
      for (const Eigen::Vector3d& p : cloud) {
        auto& [sum, n] = oracle[{std::floor(p.z() / voxel), std::floor(p.y() / voxel),
                                 std::floor(p.x() / voxel)}];
        if (n++ == 0) sum.setZero();
        sum += p;
      }
      std::vector<std::size_t> counts;
      const PointCloud out = voxel_downsample(cloud, voxel, &counts);
      ASSERT_EQ(out.size(), oracle.size()) << voxel;
      ASSERT_EQ(counts.size(), oracle.size());
      std::size_t k = 0;
      for (const auto& [key, value] : oracle) {
        EXPECT_EQ(out[k], value.first / static_cast<double>(value.second)) << voxel << " " << k;
        EXPECT_EQ(counts[k], value.second);
        ++k;
      }
    }
  }
}

TEST(VoxelDownsample, RejectsBadInput) {
  EXPECT_THROW(voxel_downsample({{0, 0, 0}}, -0.1), std::invalid_argument);
  EXPECT_THROW(voxel_downsample({{0, 0, 0}}, std::nan("")), std::invalid_argument);
  try {
    voxel_downsample({{0, 0, 0}, {0, std::nan(""), 0}}, 0.1);
    FAIL() << "NaN accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("point 1"), std::string::npos);
  }
}

TEST(Normals, OfATiltedPlaneFaceTheViewpoint) {
  const Eigen::Vector3d n = Eigen::Vector3d(0.2, -0.1, 1.0).normalized();
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coord(-0.2, 0.2);
  PointCloud points;
  for (int i = 0; i < 2000; ++i) points.push_back(coord(rng) * u + coord(rng) * v);
  points.push_back({5.0, 5.0, 5.0});  // alone: no normal
  for (const NormalConfig& config :
       {NormalConfig{.k_neighbours = 10}, NormalConfig{.radius = 0.03}}) {
    for (const double side : {1.0, -1.0}) {
      const std::vector<Eigen::Vector3d> normals =
          estimate_normals(points, config, side * Eigen::Vector3d(0, 0, 2));
      ASSERT_EQ(normals.size(), points.size());
      for (std::size_t i = 0; i + 1 < points.size(); ++i) {
        EXPECT_GT(normals[i].dot(side * n), 0.9999) << i;
      }
      if (config.k_neighbours == 0) {
        EXPECT_TRUE(normals.back().isZero());
      }
    }
  }
}

TEST(Normals, ValidateNamesTheField) {
  EXPECT_THROW(estimate_normals({}, {.k_neighbours = -1}, {}), std::invalid_argument);
  try {
    estimate_normals({}, {.radius = 0.0}, {});
    FAIL() << "zero radius accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("normals.radius"), std::string::npos);
  }
}

}  // namespace
}  // namespace vantage::perception
