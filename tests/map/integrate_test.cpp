// Scan integration in the paper's mode and in OctoMap's endpoint mode.

#include "vantage/map/integrate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

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

// A 64 x 48 depth image of the wall scene's wall with a box before it, a few pixels without depth
// (0) and some beyond the grid, integrated directly and as the points of its valid pixels in row
// order: the same grid, cell for cell, and the same counts, in both modes and with a mask.
TEST(IntegrateDepth, EqualsIntegratingThePixelsAsPoints) {
  WallScene scene;
  std::vector<std::uint16_t> depth(64 * 48);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> noise(-4, 4);
  std::vector<std::uint8_t> mask(depth.size());
  for (int v = 0; v < 48; ++v) {
    for (int u = 0; u < 64; ++u) {
      const std::size_t k = static_cast<std::size_t>(v) * 64 + u;
      const bool box = u > 20 && u < 40 && v > 10 && v < 30;
      depth[k] = static_cast<std::uint16_t>((box ? 6000 : 7500) + 10 * u + noise(rng));  // 5000/m
      if (u > 60) depth[k] = 40000;                  // 8 m: beyond the grid
      if ((u * 7 + v * 13) % 17 == 0) depth[k] = 0;  // no depth
      mask[k] = static_cast<std::uint8_t>((u + v) % 3 != 0);
    }
  }
  DepthFrame frame{.width = 64,
                   .height = 48,
                   .depth = depth,
                   .fx = 80.0,
                   .fy = 80.0,
                   .cx = 31.5,
                   .cy = 23.5,
                   .units_per_metre = 5000.0,
                   .invalid = 0};
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(0.1, Eigen::Vector3d(0.2, 0.3, 1.0).normalized()).matrix();
  pose.translation() = Eigen::Vector3d(-0.4, 0.013, 0.021);
  const Frustum view(pose, SensorFov{deg2rad(44), deg2rad(34), 0.1, 10.0});
  // The points path, as a reader hands them over: the optical frame turned into the sensor's.
  Eigen::Matrix3d R_sensor_optical;
  R_sensor_optical << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  for (const bool masked : {false, true}) {
    PointCloud points;
    for (int v = 0; v < 48; ++v) {
      for (int u = 0; u < 64; ++u) {
        const std::size_t k = static_cast<std::size_t>(v) * 64 + u;
        if (depth[k] == 0 || (masked && mask[k] == 0)) continue;
        points.push_back(pose * (R_sensor_optical * frame.optical_point(u, v, depth[k])));
      }
    }
    for (const IntegrationMode mode : {IntegrationMode::kPaper, IntegrationMode::kEndpoint}) {
      IntegrationConfig config;
      config.mode = mode;
      OccupancyGrid direct(scene.spec), via_points(scene.spec);
      const IntegrationResult a = integrate_depth(
          direct, frame, view, config,
          masked ? std::span<const std::uint8_t>(mask) : std::span<const std::uint8_t>());
      const IntegrationResult b = integrate_scan(via_points, {points, view}, config);
      std::size_t changed = 0;
      for (std::size_t i = 0; i < scene.spec.num_cells(); ++i) {
        ASSERT_EQ(direct.log_odds(i), via_points.log_odds(i)) << "cell " << i;
        changed += direct.is_unobserved(i) ? 0 : 1;
      }
      EXPECT_GT(changed, 1000u);
      EXPECT_EQ(a.left_unobserved, b.left_unobserved);
      EXPECT_EQ(a.points_inside, b.points_inside);
      EXPECT_EQ(a.points_outside, b.points_outside);
      EXPECT_GT(a.points_outside, 0u);
      EXPECT_EQ(a.hit_cells, b.hit_cells);
      EXPECT_EQ(a.missed_cells, b.missed_cells);
    }
  }
}

TEST(IntegrateDepth, StatesWhatIsWrongWithAFrame) {
  WallScene scene;
  OccupancyGrid grid(scene.spec);
  const std::vector<std::uint16_t> depth(12, 1000);
  const DepthFrame good{
      .width = 4, .height = 3, .depth = depth, .fx = 5, .fy = 5, .cx = 1.5, .cy = 1.0};
  EXPECT_NO_THROW(integrate_depth(grid, good, scene.view, {}));
  const std::pair<void (*)(DepthFrame&), const char*> spoilt[] = {
      {[](DepthFrame& f) { f.width = 5; }, "12 depth values for 5 x 3"},
      {[](DepthFrame& f) { f.fx = 0.0; }, "fx and fy"},
      {[](DepthFrame& f) { f.units_per_metre = -1.0; }, "units_per_metre"},
      {[](DepthFrame& f) { f.cy = std::nan(""); }, "cx and cy"},
  };
  for (const auto& [spoil, what] : spoilt) {
    DepthFrame frame = good;
    spoil(frame);
    try {
      integrate_depth(grid, frame, scene.view, {});
      ADD_FAILURE() << what << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  }
  const std::vector<std::uint8_t> mask(11, 1);
  EXPECT_THROW(integrate_depth(grid, good, scene.view, {}, mask), std::invalid_argument);
}

}  // namespace
}  // namespace vantage
