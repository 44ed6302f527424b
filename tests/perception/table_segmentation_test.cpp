#include "vantage/perception/table_segmentation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <numbers>
#include <stdexcept>
#include <string>

#include "synthetic_scene.hpp"

namespace vantage::perception {
namespace {
using testing::Scene;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kSigma = 0.002;  // [m] range noise

/// A labelled cloud: which input points are the table's and which the objects'.
struct Labelled {
  PointCloud points;
  std::vector<char> is_object;
  std::vector<double> true_height;  // above the table top, before noise [m]
};

void add(Labelled& cloud, const PointCloud& points, bool object, double table_z) {
  for (const Eigen::Vector3d& p : points) {
    cloud.points.push_back(p);
    cloud.is_object.push_back(object);
    cloud.true_height.push_back(p.z() - table_z);
  }
}

Labelled table_top(const Scene& scene, std::uint32_t seed) {
  Labelled cloud;
  add(cloud, testing::sample_table(scene, 20000.0, kSigma, seed), false, scene.table_z);
  add(cloud, testing::sample_objects(scene, 20000.0, kSigma, seed + 1), true, scene.table_z);
  return cloud;
}

TEST(TableSegmentation, KeepsTheObjectsAndDropsTheTable) {
  const Scene scene;
  const Labelled cloud = table_top(scene, 1);
  const TableConfig config;
  const TableSegmentation result = segment_table(cloud.points, config);
  ASSERT_TRUE(result.found);
  EXPECT_GT(result.plane.z(), std::cos(0.5 * kDeg));
  EXPECT_NEAR(-result.plane.w() / result.plane.z(), scene.table_z, 0.002);

  std::vector<char> kept(cloud.points.size(), 0);
  for (const std::size_t i : result.object_indices) kept[i] = 1;
  std::size_t objects = 0, objects_kept = 0, table_kept = 0, clear_objects_dropped = 0,
              low_objects_kept = 0;
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    if (!cloud.is_object[i]) {
      table_kept += kept[i];
      continue;
    }
    ++objects;
    objects_kept += kept[i];
    // Object points clearly above the height cut (by 3 sigma of noise) must all be kept.
    if (!kept[i] && cloud.true_height[i] > config.min_height + 3 * kSigma) ++clear_objects_dropped;
    // The lowest min_height of each side is cut by design, as the table's own noise is.
    if (kept[i] && cloud.true_height[i] < config.min_height - 3 * kSigma) ++low_objects_kept;
  }
  EXPECT_EQ(table_kept, 0u);
  EXPECT_EQ(clear_objects_dropped, 0u);
  EXPECT_EQ(low_objects_kept, 0u);
  EXPECT_GT(static_cast<double>(objects_kept), 0.9 * static_cast<double>(objects));
  EXPECT_GT(result.table_inliers, cloud.points.size() - objects - 50);
  ASSERT_EQ(result.objects.size(), result.object_indices.size());
  for (std::size_t k = 0; k < result.objects.size(); ++k) {
    EXPECT_EQ(result.objects[k], cloud.points[result.object_indices[k]]);
  }
  EXPECT_TRUE(std::is_sorted(result.object_indices.begin(), result.object_indices.end()));

  // The extent: the hull hugs the table's 1 m x 1 m top, counter-clockwise from above.
  ASSERT_GE(result.table_hull.size(), 4u);
  double area = 0.0;
  for (std::size_t e = 0; e < result.table_hull.size(); ++e) {
    const Eigen::Vector3d& a = result.table_hull[e];
    const Eigen::Vector3d& b = result.table_hull[(e + 1) % result.table_hull.size()];
    area += 0.5 * (a.x() * b.y() - a.y() * b.x());
    EXPECT_LE(a.head<2>().cwiseAbs().maxCoeff(), 0.5 + 3 * kSigma);
    EXPECT_NEAR(a.z(), scene.table_z, 0.002);
  }
  EXPECT_NEAR(area, 1.0, 0.03);
}

TEST(TableSegmentation, DropsWhatIsBesideOrBelowTheTable) {
  Scene scene;
  Labelled cloud = table_top(scene, 3);
  // A tall cabinet beside the table, its top above the table's height, and the floor below.
  Scene beside;
  beside.table_z = 0.0;
  beside.boxes = {{{0.9, 0.0}, {0.3, 0.3, 0.95}, 0.0}};
  add(cloud, testing::sample_objects(beside, 20000.0, kSigma, 7), false, scene.table_z);
  Scene floor;
  floor.table_z = 0.0;
  floor.table_half = {0.7, 0.7};
  floor.boxes.clear();
  add(cloud, testing::sample_table(floor, 4000.0, kSigma, 8), false, scene.table_z);

  const TableSegmentation result = segment_table(cloud.points, {});
  ASSERT_TRUE(result.found);
  EXPECT_NEAR(-result.plane.w() / result.plane.z(), scene.table_z, 0.002);
  for (const std::size_t i : result.object_indices) {
    ASSERT_TRUE(cloud.is_object[i]) << "kept point " << i << " at " << cloud.points[i].transpose();
  }
  EXPECT_GT(result.objects.size(), 1000u);
}

TEST(TableSegmentation, TakesTheDominantPlaneWithinTheAllowedHeights) {
  // A floor with more points than the table: it dominates unless the table's heights are given.
  Scene scene;
  Labelled cloud = table_top(scene, 5);
  Scene floor;
  floor.table_z = 0.0;
  floor.table_half = {1.0, 1.0};
  floor.boxes.clear();
  add(cloud, testing::sample_table(floor, 10000.0, kSigma, 9), false, scene.table_z);

  const TableSegmentation floor_first = segment_table(cloud.points, {});
  ASSERT_TRUE(floor_first.found);
  EXPECT_NEAR(floor_first.plane.w(), 0.0, 0.002);

  TableConfig config;
  config.min_table_z = 0.3;
  const TableSegmentation result = segment_table(cloud.points, config);
  ASSERT_TRUE(result.found);
  EXPECT_NEAR(-result.plane.w() / result.plane.z(), scene.table_z, 0.002);
}

TEST(TableSegmentation, FindsNoTableWhereNothingIsHorizontal) {
  Scene scene;
  scene.boxes.clear();
  const PointCloud flat = testing::sample_table(scene, 20000.0, kSigma, 11);
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(20 * kDeg, Eigen::Vector3d::UnitX()).matrix();
  PointCloud tilted;
  for (const Eigen::Vector3d& p : flat) tilted.push_back(tilt * p);
  const TableSegmentation result = segment_table(tilted, {});
  EXPECT_FALSE(result.found);
  EXPECT_TRUE(result.objects.empty());
  EXPECT_FALSE(segment_table({}, {}).found);
}

TEST(TableSegmentation, IsDeterministicForAnyThreadCount) {
  const Labelled cloud = table_top(Scene{}, 13);
  TableConfig one, two;
  one.num_threads = 1;
  two.num_threads = 2;
  const TableSegmentation a = segment_table(cloud.points, one);
  const TableSegmentation b = segment_table(cloud.points, two);
  const TableSegmentation c = segment_table(cloud.points, one);
  EXPECT_EQ(a.plane, b.plane);
  EXPECT_EQ(a.plane, c.plane);
  EXPECT_EQ(a.object_indices, b.object_indices);
  EXPECT_EQ(a.object_indices, c.object_indices);
  EXPECT_EQ(a.table_hull, c.table_hull);
}

TEST(TableSegmentation, RejectsBadInput) {
  PointCloud cloud = {{0, 0, 0}, {1, 0, 0}, {0, std::nan(""), 0}};
  try {
    segment_table(cloud, {});
    FAIL() << "NaN accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("point 2"), std::string::npos);
  }
  const std::pair<void (*)(TableConfig&), const char*> fields[] = {
      {[](TableConfig& c) { c.voxel_size = -1; }, "table.voxel_size"},
      {[](TableConfig& c) { c.normal_radius = 0; }, "table.normal_radius"},
      {[](TableConfig& c) { c.distance_threshold = 0; }, "table.distance_threshold"},
      {[](TableConfig& c) { c.max_angle = 2.0; }, "table.max_angle"},
      {[](TableConfig& c) { c.min_inliers = 0; }, "table.min_inliers"},
      {[](TableConfig& c) { c.min_table_z = 1.0, c.max_table_z = 0.0; }, "table.max_table_z"},
      {[](TableConfig& c) { c.max_height = 0.001; }, "table.max_height"},
      {[](TableConfig& c) { c.margin = -0.1; }, "table.margin"},
  };
  for (const auto& [spoil, field] : fields) {
    TableConfig config;
    spoil(config);
    try {
      config.validate();
      ADD_FAILURE() << field << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  }
}

// Run with --gtest_also_run_disabled_tests --gtest_filter='TableStudy.*': CPU time of
// segment_table on the synthetic table top, alone and with a 2 m x 2 m floor below it.
TEST(TableStudy, DISABLED_Timing) {
  const Scene scene;
  Labelled cloud = table_top(scene, 21);
  for (const bool with_floor : {false, true}) {
    if (with_floor) {
      Scene floor;
      floor.table_z = 0.0;
      floor.table_half = {1.0, 1.0};
      floor.boxes.clear();
      add(cloud, testing::sample_table(floor, 10000.0, kSigma, 22), false, scene.table_z);
    }
    TableConfig config;
    config.min_table_z = 0.3;
    config.num_threads = 1;
    const std::clock_t start = std::clock();
    const int runs = 5;
    std::size_t objects = 0;
    for (int run = 0; run < runs; ++run)
      objects = segment_table(cloud.points, config).objects.size();
    std::printf("%zu points%s: %.0f ms CPU per segmentation, %zu object points\n",
                cloud.points.size(), with_floor ? " (with floor)" : "",
                1e3 * static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC / runs, objects);
  }
}

}  // namespace
}  // namespace vantage::perception
