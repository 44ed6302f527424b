#include "vantage/perception/table_pose.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "synthetic_scene.hpp"

namespace vantage::perception {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// A sensor at `position` looking at the world's origin, level in roll.
Eigen::Isometry3d looking_at_origin(const Eigen::Vector3d& position) {
  const Eigen::Vector3d forward = (Eigen::Vector3d(0.0, 0.0, 0.8) - position).normalized();
  const Eigen::Vector3d left = Eigen::Vector3d::UnitZ().cross(forward).normalized();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = forward;
  T.linear().col(1) = left;
  T.linear().col(2) = forward.cross(left);
  T.translation() = position;
  return T;
}

/// The synthetic table top as a sensor at `T_world_sensor` sees it, in its frame.
PointCloud seen_from(const testing::Scene& scene, const Eigen::Isometry3d& T_world_sensor) {
  PointCloud world = testing::sample_table(scene, 20000.0, 0.002, 3);
  const PointCloud objects =
      testing::sample_objects(scene, 20000.0, 0.002, 4, T_world_sensor.translation());
  world.insert(world.end(), objects.begin(), objects.end());
  return transform(T_world_sensor.inverse(), world);
}

TEST(TablePose, RecoversHeightTiltAndUpFromTheTable) {
  const testing::Scene scene;  // the table's top at 0.75 m
  const Eigen::Isometry3d truth = looking_at_origin({-0.9, 0.3, 1.3});
  const std::optional<TablePose> pose = estimate_table_pose(seen_from(scene, truth), {});
  ASSERT_TRUE(pose.has_value());
  EXPECT_NEAR(pose->height_above_table, 1.3 - scene.table_z, 0.005);
  EXPECT_NEAR(pose->T_world_sensor.translation().z(), 1.3, 0.005);  // table_height 0.75 too
  const double true_tilt = std::asin(-truth.linear()(2, 0));
  EXPECT_NEAR(pose->tilt, true_tilt, 0.5 * kDeg);
  // Up is the world's: the sensor's axes make the same angles with it.
  EXPECT_LT((pose->T_world_sensor.linear().row(2) - truth.linear().row(2)).norm(), 0.01);
  // x is the view's direction on the table: the sensor sees no sideways component, and it lies
  // on -x, looking toward +x (the table's far side).
  EXPECT_NEAR(pose->T_world_sensor.linear()(1, 0), 0.0, 1e-9);
  EXPECT_GT(pose->T_world_sensor.linear()(0, 0), 0.0);
  EXPECT_LT(pose->T_world_sensor.translation().x(), 0.0);
  EXPECT_GT(pose->table_points, 1000u);
  EXPECT_GT(pose->object_points, 1000u);
}

TEST(TablePose, PutsTheTableAtTheStatedHeightAndTheObjectsAtTheOrigin) {
  const testing::Scene scene;
  const Eigen::Isometry3d truth = looking_at_origin({0.2, -1.0, 1.4});
  const PointCloud points = seen_from(scene, truth);
  TablePoseConfig config;
  config.table_height = 0.9;
  const std::optional<TablePose> pose = estimate_table_pose(points, config);
  ASSERT_TRUE(pose.has_value());
  // Every table point lands on z = 0.9 (within the noise), the objects' centroid above the
  // origin.
  const PointCloud table =
      transform(pose->T_world_sensor * truth.inverse(), testing::sample_table(scene, 2000, 0, 5));
  for (const Eigen::Vector3d& p : table) ASSERT_NEAR(p.z(), 0.9, 0.005);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::size_t above = 0;
  for (const Eigen::Vector3d& p : transform(pose->T_world_sensor, points)) {
    if (p.z() > 0.9 + 0.01) {
      centroid += p;
      ++above;
    }
  }
  ASSERT_GT(above, 0u);
  centroid /= static_cast<double>(above);
  EXPECT_NEAR(centroid.x(), 0.0, 0.01);
  EXPECT_NEAR(centroid.y(), 0.0, 0.01);
}

TEST(TablePose, NothingWithoutATableBelowTheSensor) {
  testing::Scene scene;
  // The table above the sensor (a ceiling, or a sensor upside down): no pose.
  const Eigen::Isometry3d below = looking_at_origin({-0.9, 0.0, 0.2});
  EXPECT_FALSE(estimate_table_pose(seen_from(scene, below), {}).has_value());
  // A wall in front of the sensor, no horizontal plane: no pose.
  PointCloud wall;
  for (int i = 0; i < 100; ++i) {
    for (int j = 0; j < 100; ++j) wall.emplace_back(1.0, -0.5 + 0.01 * i, -0.5 + 0.01 * j);
  }
  EXPECT_FALSE(estimate_table_pose(wall, {}).has_value());
}

TEST(TablePose, RefusesABadConfig) {
  TablePoseConfig config;
  config.table_height = std::nan("");
  EXPECT_THROW(config.validate(), std::invalid_argument);
  config = {};
  config.max_tilt = 90.0 * kDeg;
  EXPECT_THROW(config.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace vantage::perception
