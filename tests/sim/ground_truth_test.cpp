#include "vantage/sim/ground_truth.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "test_scenes.hpp"
#include "vantage/views/ring.hpp"

namespace vantage::sim {
namespace {

using testing::box_shape;
using testing::empty_scene;
using testing::quiet_rgbd;

std::size_t count_occupied(const std::vector<std::uint8_t>& occupied) {
  return static_cast<std::size_t>(std::count(occupied.begin(), occupied.end(), 1));
}

/// Cells whose open interval meets (lo, hi) along one axis, clipped to [0, n).
long cells_across(double lo, double hi, double origin, double res, int n) {
  const long first = std::max(0L, static_cast<long>(std::floor((lo - origin) / res)));
  const long last =
      std::min(static_cast<long>(n), static_cast<long>(std::ceil((hi - origin) / res)));
  return std::max(0L, last - first);
}

TEST(Voxelize, BoxMatchesTheAnalyticCount) {
  GridSpec grid;
  grid.origin = {-2.5, -2.5, -2.5};
  grid.resolution = 0.0625;
  grid.dims = {80, 80, 80};
  struct Case {
    Eigen::Vector3d lo, hi;
  };
  const std::vector<Case> cases = {
      {{0.01, 0.02, 0.03}, {0.51, 0.33, 0.97}},     // unaligned
      {{-1.0, -0.5, 0.25}, {0.5, 0.0, 1.0}},        // every face on a cell boundary
      {{-0.03, -1.7, 0.0}, {0.0, -1.6, 0.0625}},    // thin, two faces on boundaries
      {{2.2, 2.3, -3.0}, {3.0, 2.4, -2.3}},         // partly outside the grid
      {{-0.2, -0.2, -0.2}, {-0.18, -0.19, -0.17}},  // inside one cell
  };
  for (const Case& c : cases) {
    const auto occupied = voxelize({box_shape(c.lo, c.hi)}, grid, 1);
    long expected = 1;
    for (int a = 0; a < 3; ++a) {
      expected *= cells_across(c.lo[a], c.hi[a], grid.origin[a], grid.resolution, grid.dims[a]);
    }
    EXPECT_EQ(count_occupied(occupied), static_cast<std::size_t>(expected))
        << c.lo.transpose() << " - " << c.hi.transpose();
  }
}

TEST(Voxelize, RotatedBoxLiesBetweenItsInnerAndOuterCells) {
  const GridSpec grid = GridSpec::centered(Eigen::Vector3d::Zero(), 0.05, {60, 60, 60});
  Shape shape;
  const Eigen::Vector3d size(0.8, 0.5, 0.6);
  const Eigen::Isometry3d T = pose_from_xyz_rpy({0.03, -0.02, -0.3}, {0.3, -0.2, 0.7});
  shape.mesh_world = transformed(make_box(size), T);
  const auto occupied = voxelize({shape}, grid, 2);
  // Oracle: a cell lies wholly inside if its 8 corners do; it overlaps only if the box's
  // separating test fails, so a cell whose centre is inside must be occupied, and a cell farther
  // than half its diagonal from the box must not be.
  const Eigen::Isometry3d T_box_world = T.inverse();
  auto distance_outside = [&](const Eigen::Vector3d& p_world) {
    Eigen::Vector3d p = T_box_world * p_world;
    p.z() -= size.z() / 2;
    return (p.cwiseAbs() - size / 2).cwiseMax(0.0).norm();
  };
  std::size_t inside_centres = 0;
  for (std::size_t i = 0; i < grid.num_cells(); ++i) {
    const Eigen::Vector3d c = grid.center(grid.unravel(i));
    const double d = distance_outside(c);
    if (d == 0.0) {
      ++inside_centres;
      ASSERT_EQ(occupied[i], 1) << c.transpose();
    } else if (d > grid.resolution * std::sqrt(3.0) / 2) {
      ASSERT_EQ(occupied[i], 0) << c.transpose();
    }
  }
  // Interior cells come from the flood fill, not from the faces: most of the volume.
  EXPECT_GT(inside_centres, static_cast<std::size_t>(0.8 * size.prod() / std::pow(0.05, 3)));
}

TEST(Voxelize, SurfaceOfABoxIsItsShell) {
  GridSpec grid;
  grid.origin = {-1, -1, -1};
  grid.resolution = 0.125;
  grid.dims = {16, 16, 16};
  const auto occupied = voxelize({box_shape({-0.5, -0.25, 0.0}, {0.25, 0.5, 0.5})}, grid);
  ASSERT_EQ(count_occupied(occupied), 6u * 6u * 4u);
  EXPECT_EQ(surface_cells(grid, occupied).size(), 6u * 6u * 4u - 4u * 4u * 2u);
}

TEST(Voxelize, SphereCellsTouchTheBall) {
  const GridSpec grid = GridSpec::centered(Eigen::Vector3d::Zero(), 0.1, {30, 30, 30});
  const Sphere ball{{0.05, 0.12, -0.31}, 0.73};
  const auto occupied = voxelize({testing::sphere_shape(ball.center, ball.radius)}, grid);
  std::size_t count = 0;
  for (std::size_t i = 0; i < grid.num_cells(); ++i) {
    const Eigen::Vector3d c = grid.center(grid.unravel(i));
    const double d = (c - ball.center).norm();
    // Cells whose centre is inside must be in; cells wholly outside must not.
    if (d < ball.radius) {
      ASSERT_EQ(occupied[i], 1);
    }
    if (d > ball.radius + 0.1 * std::sqrt(3.0) / 2) {
      ASSERT_EQ(occupied[i], 0);
    }
    count += occupied[i];
  }
  const double volume_cells = 4.0 / 3.0 * std::numbers::pi * std::pow(0.73, 3) / 1e-3;
  EXPECT_GT(static_cast<double>(count), volume_cells);
}

TEST(Observable, OnlyTheFacesASensorCanSee) {
  SensorConfig sensor = quiet_rgbd();
  Scene scene = empty_scene(sensor);
  scene.grid.origin = {-1, -1, 0};
  scene.grid.resolution = 0.0625;
  scene.grid.dims = {32, 32, 16};
  // A block in the middle; a second one hides behind it.
  scene.shapes.push_back(box_shape({-0.25, -0.25, 0.0}, {0.25, 0.25, 0.5}));
  scene.shapes.push_back(box_shape({0.5, -0.125, 0.0}, {0.75, 0.125, 0.25}));
  const World world(scene);
  const auto occupied = voxelize(scene.shapes, scene.grid);
  const auto surface = surface_cells(scene.grid, occupied);
  // One view from -x, looking along +x at the block.
  const std::vector<Viewpoint> views = {
      {{Frustum(look_at({-2.0, 0.0, 0.25}, {0.0, 0.0, 0.25}), scene.fov())}}};
  const auto seen = observable_cells(world, scene.grid, surface, views);
  const std::set<std::uint32_t> seen_set(seen.begin(), seen.end());
  ASSERT_FALSE(seen.empty());
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  for (const std::uint32_t c : seen) {
    EXPECT_TRUE(std::binary_search(surface.begin(), surface.end(), c));
    // Only the block's face toward the sensor (x cell 12, from -0.25 m) is visible.
    EXPECT_EQ(scene.grid.unravel(c).x(), 12) << scene.grid.unravel(c).transpose();
  }
  EXPECT_EQ(seen.size(), 8u * 8u);  // the face, 8 x 8 cells
  // From a second view above the far side, the hidden block shows too.
  const std::vector<Viewpoint> two = {
      views[0], {{Frustum(look_at({2.0, 0.0, 1.5}, {0.6, 0.0, 0.1}), scene.fov())}}};
  const auto more = observable_cells(world, scene.grid, surface, two);
  EXPECT_GT(more.size(), seen.size());
  EXPECT_TRUE(std::includes(more.begin(), more.end(), seen.begin(), seen.end()));
}

TEST(GroundTruth, TableTopScansHitOnlyTrulyOccupiedCells) {
  Scene scene = load_scene("tabletop-2");
  scene.sensor.noise = {};
  const World world(scene);
  const GroundTruth gt = compute_ground_truth(world);
  EXPECT_EQ(gt.viewpoints, 40u);
  EXPECT_GT(gt.occupied_count, 1000u);
  EXPECT_LT(gt.observable.size(), gt.surface.size());
  EXPECT_GT(gt.observable.size(), gt.surface.size() / 3);
  // Oracle: a noise-free scan's every point off the table lies in a truly occupied cell (nudged
  // along its ray into the surface), and almost all of those cells count as observable.
  std::set<std::uint32_t> hit;
  for (std::size_t k = 0; k < 3; ++k) {
    const SimulatedScan scan = world.scan(scene.start_poses[3 * k], k);
    const Eigen::Vector3d o = scan.T_world_sensor_true.translation();
    for (const Eigen::Vector3d& p : scan.points_sensor) {
      const Eigen::Vector3d p_world = scan.T_world_sensor_true * p;
      const Eigen::Vector3d nudged = p_world + (p_world - o).normalized() * 1e-6;
      const auto cell = gt.grid.find(nudged);
      if (!cell || p_world.z() < 0.75 + 1e-6) continue;  // outside the grid, or the table
      const std::size_t i = gt.grid.linear(*cell);
      ASSERT_EQ(gt.occupied[i], 1) << p_world.transpose();
      hit.insert(static_cast<std::uint32_t>(i));
    }
  }
  ASSERT_GT(hit.size(), 500u);
  std::size_t observable_hits = 0;
  for (const std::uint32_t c : hit) {
    observable_hits += std::binary_search(gt.observable.begin(), gt.observable.end(), c);
  }
  EXPECT_GT(static_cast<double>(observable_hits), 0.95 * static_cast<double>(hit.size()));
}

TEST(GroundTruth, SameOnAnyThreadCount) {
  const World world(load_scene("tabletop-1"));
  const GroundTruth one = compute_ground_truth(world, 1);
  const GroundTruth two = compute_ground_truth(world, 2);
  EXPECT_EQ(one.occupied, two.occupied);
  EXPECT_EQ(one.surface, two.surface);
  EXPECT_EQ(one.observable, two.observable);
}

constexpr const char* kTwoRooms = R"(name: two-rooms
kind: office
grid: {origin: [0, 0, 0], resolution: 0.1, dims: [100, 50, 20]}
floor: {size: [10, 5], center: [5, 2.5]}
walls: {height: 2.0, thickness: 0.1}
rooms:
  - {name: open, min: [0.05, 0.05], max: [5, 4.95]}
  - {name: closed, min: [5, 0.05], max: [9.95, 4.95]}
objects:
  - {type: cabinet, size: [1.0, 1.0, 1.0], pose: [2.5, 2.5, 0]}
sensor: kinect
mount: {height: 1.0, pitch_deg: 0}
robot: {footprint: 0.6, stop_spacing: 0.25}
candidates: {generator: frontier}
start_poses: [[1, 1, 0]]
)";

TEST(GroundTruth, ReachableStopsStayInTheConnectedFreeSpace) {
  const Scene scene = parse_scene(kTwoRooms, "two-rooms", ".");
  const auto occupied = voxelize(scene.shapes, scene.grid);
  const auto stops = reachable_stops(scene, occupied);
  ASSERT_GT(stops.size(), 100u);
  for (const Eigen::Vector2d& s : stops) {
    EXPECT_LT(s.x(), 5.0 - 0.05 - 0.3) << s.transpose();  // never in the closed room
    EXPECT_GT(s.x(), 0.1 + 0.3 - 1e-9);
    // Clear of the cabinet by half the footprint.
    const Eigen::Vector2d gap =
        ((s - Eigen::Vector2d(2.5, 2.5)).cwiseAbs() - Eigen::Vector2d(0.5, 0.5)).cwiseMax(0.0);
    EXPECT_GT(gap.norm(), 0.3 - 1e-9) << s.transpose();
  }
  Scene blocked = scene;
  blocked.start_poses = {blocked.mount.sensor_pose(2.5, 2.5)};  // inside the cabinet
  EXPECT_THROW(reachable_stops(blocked, occupied), std::invalid_argument);
}

TEST(GroundTruth, OfficeObservableCellsComeFromSweepsAtReachableStops) {
  Scene scene = parse_scene(kTwoRooms, "two-rooms", ".");
  scene.robot.stop_spacing = 0.5;
  scene.sensor.width = 64;  // the ground truth uses frusta, not pixels
  scene.sensor.height = 48;
  const World world(scene);
  const GroundTruth gt = compute_ground_truth(world);
  ASSERT_GT(gt.viewpoints, 10u);
  ASSERT_FALSE(gt.observable.empty());
  for (const std::uint32_t c : gt.observable) {
    // Nothing inside the closed room, whose walls' inner faces start at x = 5.05.
    EXPECT_LT(gt.grid.center(gt.grid.unravel(c)).x(), 5.05) << gt.grid.unravel(c).transpose();
  }
}

}  // namespace
}  // namespace vantage::sim
