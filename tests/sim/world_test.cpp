#include "vantage/sim/world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "test_scenes.hpp"
#include "vantage/views/ring.hpp"

namespace vantage::sim {
namespace {

using testing::box_shape;
using testing::empty_scene;
using testing::quiet_range_finder;
using testing::quiet_rgbd;
using testing::sphere_shape;

/// A wall whose face x = distance faces a sensor at the origin looking along +x.
Scene wall_scene(const SensorConfig& sensor, double distance) {
  Scene scene = empty_scene(sensor);
  scene.shapes.push_back(box_shape({distance, -50, -50}, {distance + 1, 50, 50}));
  return scene;
}

struct Spread {
  double mean = 0.0;
  double sd = 0.0;
};

Spread spread(const std::vector<double>& v) {
  Spread s;
  s.mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
  double ss = 0.0;
  for (const double x : v) ss += (x - s.mean) * (x - s.mean);
  s.sd = std::sqrt(ss / static_cast<double>(v.size() - 1));
  return s;
}

TEST(World, RgbdDepthOfAPlaneIsExactWithoutNoise) {
  const SensorConfig sensor = quiet_rgbd();
  const World world(wall_scene(sensor, 2.0));
  const SimulatedScan scan = world.scan(Eigen::Isometry3d::Identity(), 1);
  ASSERT_EQ(scan.rays, 160u * 120u);
  ASSERT_EQ(scan.points_sensor.size(), scan.rays);  // every pixel sees the wall within 3.5 m
  for (const Eigen::Vector3d& p : scan.points_sensor) ASSERT_NEAR(p.x(), 2.0, 1e-5);
}

TEST(World, RangeFinderRangeToATiltedPlaneIsExactWithoutNoise) {
  const SensorConfig sensor = quiet_range_finder();
  const World world(wall_scene(sensor, 1.5));
  // Turn the sensor by 20 degrees: ranges vary across the plane; the points must stay on it.
  const Eigen::Isometry3d T(Eigen::AngleAxisd(deg2rad(20), Eigen::Vector3d::UnitZ()));
  const SimulatedScan scan = world.scan(T, 7);
  ASSERT_GT(scan.points_sensor.size(), 1000u);
  for (const Eigen::Vector3d& p : scan.points_world()) ASSERT_NEAR(p.x(), 1.5, 1e-5);
}

TEST(World, SphereSurfaceIsExactWithoutNoise) {
  for (const SensorConfig& sensor : {quiet_rgbd(), quiet_range_finder()}) {
    Scene scene = empty_scene(sensor);
    const Eigen::Vector3d center(2.0, 0.3, -0.2);
    scene.shapes.push_back(sphere_shape(center, 0.5));
    const World world(scene);
    const Eigen::Isometry3d T = look_at(Eigen::Vector3d(0, 0, 0.1), center);
    const SimulatedScan scan = world.scan(T, 3);
    ASSERT_GT(scan.points_sensor.size(), 100u) << sensor.name;
    for (const Eigen::Vector3d& p : scan.points_world()) {
      ASSERT_NEAR((p - center).norm(), 0.5, 1e-5) << sensor.name;
    }
  }
}

TEST(World, RangeNoiseSpreadMatchesSigma) {
  SensorConfig sensor = quiet_range_finder();
  sensor.noise.sigma = 0.01;
  const World world(wall_scene(sensor, 1.5));
  const SimulatedScan scan = world.scan(Eigen::Isometry3d::Identity(), 11);
  // Each beam's true range to the plane x = 1.5 is 1.5 / cos(angle to x).
  std::vector<double> errors;
  for (const Eigen::Vector3d& p : scan.points_sensor) {
    const Eigen::Vector3d d = p.normalized();
    errors.push_back(p.norm() - 1.5 / d.x());
  }
  ASSERT_GT(errors.size(), 3000u);
  const Spread s = spread(errors);
  EXPECT_NEAR(s.mean, 0.0, 4 * 0.01 / std::sqrt(static_cast<double>(errors.size())));
  EXPECT_NEAR(s.sd, 0.01, 0.01 * 0.05);
}

TEST(World, RgbdDepthNoiseGrowsWithDepthAsTheModelSays) {
  SensorConfig sensor = quiet_rgbd();
  sensor.noise = kinect_sensor().noise;
  for (const double depth : {1.0, 3.0}) {
    const World world(wall_scene(sensor, depth));
    const SimulatedScan scan = world.scan(Eigen::Isometry3d::Identity(), 5);
    std::vector<double> errors;
    for (const Eigen::Vector3d& p : scan.points_sensor) errors.push_back(p.x() - depth);
    ASSERT_GT(errors.size(), 15000u);
    const double sigma = sensor.noise.sigma_at(depth);
    const Spread s = spread(errors);
    EXPECT_NEAR(s.sd, sigma, sigma * 0.05) << "depth " << depth;
    EXPECT_NEAR(s.mean, 0.0, 5 * sigma / std::sqrt(static_cast<double>(errors.size())));
  }
}

TEST(World, FarAwayPosesAreRefusedNotPassedToEmbree) {
  // Embree aborts on ray origins beyond ~1.8e18 (its ray.valid() assertion); the world refuses
  // any origin beyond 1e5 m with a line that says which coordinate.
  const SensorConfig sensor = quiet_rgbd();
  const World world(wall_scene(sensor, 2.0));
  for (const double x : {1e20, -1e6, 1e300}) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation().x() = x;
    try {
      (void)world.scan(T, 1);
      FAIL() << "a scan from x = " << x << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("x = "), std::string::npos) << e.what();
    }
    EXPECT_THROW((void)world.cast(T.translation(), Eigen::Vector3d::UnitX(), 5.0),
                 std::invalid_argument);
    EXPECT_THROW((void)world.occluded(T.translation(), Eigen::Vector3d::UnitX(), 5.0),
                 std::invalid_argument);
  }
  Eigen::Isometry3d near = Eigen::Isometry3d::Identity();
  near.translation().z() = 9e4;  // far, but within range: a valid (empty) scan
  EXPECT_EQ(world.scan(near, 1).points_sensor.size(), 0u);
}

TEST(World, RaysThatHitNothingGiveNoPoints) {
  const SensorConfig sensor = quiet_rgbd(64, 48);
  Scene scene = empty_scene(sensor);
  // Behind the sensor, and beyond its range: nothing to see.
  scene.shapes.push_back(sphere_shape({-2.0, 0, 0}, 0.5));
  scene.shapes.push_back(box_shape({3.6, -10, -10}, {4.0, 10, 10}));
  const World world(scene);
  const SimulatedScan scan = world.scan(Eigen::Isometry3d::Identity(), 1);
  EXPECT_EQ(scan.rays, 64u * 48u);
  EXPECT_TRUE(scan.points_sensor.empty());
}

TEST(World, OnlyTheRaysThatHitGivePoints) {
  const SensorConfig sensor = quiet_rgbd(64, 48);
  Scene scene = empty_scene(sensor);
  // A wall only on the sensor's left (y > 0): exactly the left half of the columns hit it.
  scene.shapes.push_back(box_shape({2.0, 0.0, -5}, {3.0, 5.0, 5}));
  const World world(scene);
  const SimulatedScan scan = world.scan(Eigen::Isometry3d::Identity(), 1);
  EXPECT_EQ(scan.points_sensor.size(), 32u * 48u);
  for (const Eigen::Vector3d& p : scan.points_sensor) EXPECT_GT(p.y(), 0.0);
}

TEST(World, PointsLieInTheSensorsFrustumAndRange) {
  SensorConfig sensor = kinect_sensor();
  sensor.width = 80;
  sensor.height = 60;
  Scene scene = empty_scene(sensor);
  scene.shapes.push_back(box_shape({0.2, -0.35, -0.1}, {0.3, -0.15, 0.1}));  // closer than 0.5 m
  scene.shapes.push_back(box_shape({1.0, 0.0, -5}, {1.2, 5.0, 5}));
  scene.shapes.push_back(box_shape({4.0, -5.0, -5}, {4.2, 0.0, 5}));  // beyond 3.5 m
  const World world(scene);
  const Eigen::Isometry3d T = look_at({-0.1, 0.05, 0.02}, {1, 0.2, 0.0});
  const SimulatedScan scan = world.scan(T, 9);
  ASSERT_FALSE(scan.points_sensor.empty());
  const Frustum view = scan.view();
  for (const Eigen::Vector3d& p : scan.points_world()) EXPECT_TRUE(view.contains(p));
}

TEST(World, SameSeedSameScanOnAnyThreadCount) {
  SensorConfig sensor = kinect_sensor();
  Scene scene = wall_scene(sensor, 2.0);
  scene.shapes.push_back(sphere_shape({1.5, 0.2, 0.1}, 0.3));
  scene.pose_noise = {0.05, 0.05, deg2rad(2.0)};
  const World one(scene, {1});
  const World two(scene, {2});
  const Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const SimulatedScan a = one.scan(T, 42), b = two.scan(T, 42), c = two.scan(T, 43);
  EXPECT_EQ(a.points_sensor, b.points_sensor);
  EXPECT_TRUE(a.T_world_sensor_noisy.isApprox(b.T_world_sensor_noisy, 0.0));
  EXPECT_NE(a.points_sensor, c.points_sensor);
}

TEST(World, PoseNoiseHasTheConfiguredSpreadAndIsOffByDefault) {
  SensorConfig sensor = quiet_rgbd(8, 6);
  Scene scene = wall_scene(sensor, 2.0);
  const Eigen::Isometry3d T = look_at({0.5, -0.2, 1.0}, {2, 0, 1});
  {
    const World world(scene);
    const SimulatedScan scan = world.scan(T, 3);
    EXPECT_TRUE(scan.T_world_sensor_noisy.isApprox(scan.T_world_sensor_true, 0.0));
  }
  scene.pose_noise = {0.02, 0.05, deg2rad(3.0)};
  const World world(scene);
  std::vector<double> dx, dy, dz, dyaw;
  for (std::uint64_t seed = 0; seed < 4000; ++seed) {
    const Eigen::Isometry3d noisy = world.noisy_pose(T, seed);
    const Eigen::Vector3d d = noisy.translation() - T.translation();
    dx.push_back(d.x());
    dy.push_back(d.y());
    dz.push_back(d.z());
    const Eigen::Matrix3d R = noisy.linear() * T.linear().transpose();  // a turn about world z
    dyaw.push_back(std::atan2(R(1, 0), R(0, 0)));
    EXPECT_NEAR(R(2, 2), 1.0, 1e-12);
  }
  EXPECT_NEAR(spread(dx).sd, 0.02, 0.02 * 0.06);
  EXPECT_NEAR(spread(dy).sd, 0.05, 0.05 * 0.06);
  EXPECT_NEAR(spread(dyaw).sd, deg2rad(3.0), deg2rad(3.0) * 0.06);
  EXPECT_EQ(spread(dz).sd, 0.0);
}

TEST(World, SweepCoversTheFullCircleAndMergesIntoTheFirstFrame) {
  SensorConfig sensor = quiet_rgbd(40, 30);
  sensor.sweep_steps = 8;
  Scene scene = empty_scene(sensor);
  // A square room 4 m wide around the sensor.
  scene.shapes.push_back(box_shape({-2.1, -2.1, -3}, {-2.0, 2.1, 3}));
  scene.shapes.push_back(box_shape({2.0, -2.1, -3}, {2.1, 2.1, 3}));
  scene.shapes.push_back(box_shape({-2.0, -2.1, -3}, {2.0, -2.0, 3}));
  scene.shapes.push_back(box_shape({-2.0, 2.0, -3}, {2.0, 2.1, 3}));
  const World world(scene);
  const Eigen::Isometry3d T = pose_from_xyz_rpy({0.3, -0.1, 0.0}, {0, 0, deg2rad(10)});
  const SimulatedSweep sweep = world.sweep(T, 5);
  ASSERT_EQ(sweep.steps.size(), 8u);
  std::size_t total = 0;
  for (const SimulatedScan& step : sweep.steps) {
    EXPECT_EQ(step.points_sensor.size(), 40u * 30u);
    total += step.points_sensor.size();
  }
  EXPECT_EQ(sweep.points_sensor.size(), total);
  // Every merged point lies on a wall's inner face, and every direction is covered.
  std::vector<int> sectors(36, 0);
  for (const Eigen::Vector3d& p : sweep.points_world()) {
    EXPECT_NEAR(std::max(std::abs(p.x()), std::abs(p.y())), 2.0, 1e-5);
    const Eigen::Vector3d d = p - T.translation();
    const double bearing = std::atan2(d.y(), d.x()) + std::numbers::pi;
    ++sectors[static_cast<std::size_t>(std::min(35.0, bearing / (2 * std::numbers::pi) * 36))];
  }
  for (const int count : sectors) EXPECT_GT(count, 0);
}

}  // namespace
}  // namespace vantage::sim
