// Endpoint integration against OctoMap's OcTree::insertPointCloud on the same clouds and
// resolution: the free/occupied classes agree on the cells both know.

#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <iostream>
#include <random>

#include "vantage/map/integrate.hpp"

namespace vantage {
namespace {

// Points on three spheres and a floor patch, seen from `origin`.
PointCloud random_scene_cloud(std::mt19937_64& rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  PointCloud cloud;
  const Eigen::Vector3d centres[] = {{0.3, 0.1, 0.2}, {-0.2, 0.3, 0.1}, {0.0, -0.3, 0.3}};
  for (const Eigen::Vector3d& c : centres) {
    for (int i = 0; i < 4000; ++i) {
      cloud.push_back(c + 0.12 * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized());
    }
  }
  for (int i = 0; i < 6000; ++i) cloud.emplace_back(u(rng), u(rng), -0.05);
  return cloud;
}

TEST(IntegrateVsOctoMap, EndpointClassesAgreeOnCellsBothKnow) {
  const double res = 0.02;
  GridSpec spec;  // aligned to OctoMap's key grid: cell boundaries at multiples of res
  spec.resolution = res;
  spec.origin = Eigen::Vector3d(-40, -40, -10) * res;
  spec.dims = {80, 80, 40};
  OccupancyGrid grid(spec);
  octomap::OcTree tree(res);
  tree.setProbHit(0.7);
  tree.setProbMiss(0.4);
  tree.setClampingThresMin(0.12);
  tree.setClampingThresMax(0.97);

  std::mt19937_64 rng(2024);
  const Eigen::Vector3d origins[] = {{1.2, 0.1, 0.5}, {-0.9, -0.8, 0.6}};
  IntegrationConfig config;
  config.mode = IntegrationMode::kEndpoint;
  for (const Eigen::Vector3d& origin : origins) {
    const PointCloud cloud = random_scene_cloud(rng);
    octomap::Pointcloud octo_cloud;
    for (const Eigen::Vector3d& p : cloud) {
      octo_cloud.push_back(static_cast<float>(p.x()), static_cast<float>(p.y()),
                           static_cast<float>(p.z()));
    }
    tree.insertPointCloud(
        octo_cloud, octomap::point3d(static_cast<float>(origin.x()), static_cast<float>(origin.y()),
                                     static_cast<float>(origin.z())));
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = origin;
    integrate_scan(grid, {cloud, Frustum(pose, SensorFov{})}, config);
  }

  std::size_t both = 0, agree = 0, occupied = 0;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const CellState ours = grid.state(i);
    if (ours == CellState::kUnobserved) continue;
    const Eigen::Vector3d c = spec.center(spec.unravel(i));
    const octomap::OcTreeNode* node = tree.search(c.x(), c.y(), c.z());
    if (node == nullptr) continue;
    ++both;
    const bool octo_occupied = tree.isNodeOccupied(node);
    agree += octo_occupied == (ours == CellState::kOccupied);
    occupied += octo_occupied;
  }
  ASSERT_GT(both, 20000u);
  ASSERT_GT(occupied, 2000u);
  const double agreement = static_cast<double>(agree) / static_cast<double>(both);
  EXPECT_GE(agreement, 0.99) << agree << " of " << both << " cells agree";
  std::cout << "agreement with OctoMap: " << agree << " of " << both << " cells ("
            << 100.0 * agreement << "%)\n";
}

}  // namespace
}  // namespace vantage
