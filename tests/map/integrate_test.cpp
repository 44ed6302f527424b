// Scan integration in the paper's mode and in OctoMap's endpoint mode.

#include "vantage/map/integrate.hpp"

#include <gtest/gtest.h>

#include <random>

namespace vantage {
namespace {

// A 2 m deep room of 0.05 m cells; the sensor stands 0.5 m in front of it looking along +x at a
// wall 1 m in.
struct WallScene {
  GridSpec spec;
  Frustum view;
  PointCloud wall;

  WallScene() {
    spec.origin = {0.0, -0.5, -0.5};
    spec.resolution = 0.05;
    spec.dims = {40, 20, 20};
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(-0.5, 0.0, 0.0);
    view = Frustum(pose, SensorFov{deg2rad(40), deg2rad(40), 0.1, 5.0});
    // A dense wall patch at x = 1.0 m, |y|, |z| <= 0.2 m.
    for (double y = -0.2; y <= 0.2; y += 0.01) {
      for (double z = -0.2; z <= 0.2; z += 0.01) wall.emplace_back(1.0125, y, z);
    }
  }
};

TEST(Integrate, PaperModeMarksHitsFreeSpaceAndKeepsTheShadow) {
  WallScene scene;
  OccupancyGrid grid(scene.spec);
  IntegrationConfig config;
  const IntegrationResult result = integrate_scan(grid, {scene.wall, scene.view}, config);
  const GridSpec& spec = grid.spec();
  EXPECT_EQ(grid.state(spec.linear(spec.index_of({1.0125, 0.0, 0.0}))), CellState::kOccupied);
  EXPECT_EQ(grid.state(spec.linear(spec.index_of({0.5, 0.0, 0.0}))), CellState::kFree);
  EXPECT_EQ(grid.state(spec.linear(spec.index_of({1.5, 0.0, 0.0}))), CellState::kUnobserved);
  // Outside the frustum nothing changes.
  EXPECT_EQ(grid.state(spec.linear(spec.index_of({0.1, 0.45, 0.45}))), CellState::kUnobserved);
  EXPECT_EQ(result.points_inside, scene.wall.size());
  EXPECT_EQ(result.left_unobserved.size(),
            result.hit_cells + result.filled_cells + result.missed_cells);
  EXPECT_EQ(grid.counts().unobserved, spec.num_cells() - result.left_unobserved.size());
  EXPECT_TRUE(std::is_sorted(result.left_unobserved.begin(), result.left_unobserved.end()));
}

TEST(Integrate, EndpointModeCarvesAlongRays) {
  WallScene scene;
  OccupancyGrid grid(scene.spec);
  IntegrationConfig config;
  config.mode = IntegrationMode::kEndpoint;
  const IntegrationResult result = integrate_scan(grid, {scene.wall, scene.view}, config);
  const GridSpec& spec = grid.spec();
  EXPECT_EQ(grid.state(spec.linear(spec.index_of({1.0125, 0.0, 0.0}))), CellState::kOccupied);
  EXPECT_EQ(grid.state(spec.linear(spec.index_of({0.5, 0.0, 0.0}))), CellState::kFree);
  EXPECT_EQ(grid.state(spec.linear(spec.index_of({1.5, 0.0, 0.0}))), CellState::kUnobserved);
  // Free space is carved only along rays, not across the frustum's empty corners.
  EXPECT_EQ(grid.state(spec.linear(spec.index_of({0.9, 0.3, 0.3}))), CellState::kUnobserved);
  EXPECT_EQ(result.left_unobserved.size(), result.hit_cells + result.missed_cells);
}

TEST(Integrate, SameResultForAnyThreadCount) {
  WallScene scene;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 0.02);
  for (Eigen::Vector3d& p : scene.wall) p.x() += noise(rng);
  for (const IntegrationMode mode : {IntegrationMode::kPaper, IntegrationMode::kEndpoint}) {
    OccupancyGrid a(scene.spec), b(scene.spec);
    IntegrationConfig config;
    config.mode = mode;
    config.num_threads = 1;
    const auto ra = integrate_scan(a, {scene.wall, scene.view}, config);
    config.num_threads = 2;
    const auto rb = integrate_scan(b, {scene.wall, scene.view}, config);
    EXPECT_EQ(ra.left_unobserved, rb.left_unobserved);
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a.log_odds(i), b.log_odds(i));
  }
}

TEST(Integrate, ANonFinitePointIsRejectedAndTheGridIsUntouched) {
  WallScene scene;
  scene.wall[17].y() = std::nan("");
  OccupancyGrid grid(scene.spec);
  try {
    integrate_scan(grid, {scene.wall, scene.view}, IntegrationConfig{});
    FAIL() << "NaN accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("point 17"), std::string::npos) << e.what();
  }
  EXPECT_EQ(grid.counts().unobserved, grid.size());
}

TEST(Integrate, PointsOutsideTheGridAreCountedAndTheirRaysStillCarve) {
  WallScene scene;
  for (Eigen::Vector3d& p : scene.wall) p.x() = 3.0;  // beyond the grid's far face at 2 m
  OccupancyGrid grid(scene.spec);
  IntegrationConfig config;
  config.mode = IntegrationMode::kEndpoint;
  const IntegrationResult result = integrate_scan(grid, {scene.wall, scene.view}, config);
  EXPECT_EQ(result.points_outside, scene.wall.size());
  EXPECT_EQ(result.hit_cells, 0u);
  EXPECT_GT(result.missed_cells, 0u);
}

}  // namespace
}  // namespace vantage
