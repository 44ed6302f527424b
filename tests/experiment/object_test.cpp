// Objects on a view sphere (docs/objects.md) explored end to end: the protocol's run covers the
// object's visible surface, travels on the sphere, and keeps the yardstick's invariants.

#include <gtest/gtest.h>

#include "vantage/experiment/exploration.hpp"
#include "vantage/sim/object_scene.hpp"
#include "vantage/sim/scene.hpp"

namespace vantage {
namespace {

ExplorationResult explore_bunny(bool oracle, int scans) {
  const sim::Scene scene = sim::single_object_scene("bunny");
  ExplorationConfig config;
  config.planner.method = PlannerMethod::kGreedy;
  config.greedy_oracle = oracle;
  config.scans = scans;
  config.seed = 11;
  config.start = 2;
  config.pose_noise.reset();      // the arm's poses, as the field's protocol takes them
  config.coverage_tolerance = 0;  // MA-SCVP's: a point in the cell
  config.mapper = default_mapper_config(scene);
  config.mapper.keep_object_cloud = true;
  Mapper mapper(scene.grid, config.mapper);
  return explore(scene, config, mapper);
}

TEST(Objects, TheGreedyOracleCoversTheBunnyOnItsSphereInAFewViews) {
  const ExplorationResult run = explore_bunny(true, 8);
  ASSERT_EQ(run.scans.size(), 8u) << run.stop_reason;
  ASSERT_EQ(run.candidates.size(), 32u);
  EXPECT_GT(run.visible_surface_cells, 1000u);
  EXPECT_LE(run.visible_surface_cells, run.surface_cells);
  const sim::Scene scene = sim::single_object_scene("bunny");
  const TravelRule arc{TravelRule::Kind::kSphereArc, scene.mount.target, scene.view_sphere->radius};
  double last = 0.0;
  for (std::size_t k = 0; k < run.scans.size(); ++k) {
    const ScanRecord& r = run.scans[k];
    ASSERT_TRUE(r.surface_coverage.has_value());
    EXPECT_GE(*r.surface_coverage, last - 1e-12) << "scan " << r.scan;  // points only add
    last = *r.surface_coverage;
    if (k > 0) {
      // Travel is the arc on the sphere between the two views, never through the object.
      EXPECT_NEAR(
          r.travel,
          arc(run.scans[k - 1].T_world_sensor.translation(), r.T_world_sensor.translation()), 1e-9);
      // The path the page draws is that arc: on the sphere, as long as the travel.
      ASSERT_GE(r.path.size(), 2u);
      double drawn = 0.0;
      for (std::size_t i = 0; i < r.path.size(); ++i) {
        EXPECT_NEAR((r.path[i] - arc.center).norm(), arc.radius, 1e-9);
        if (i > 0) drawn += (r.path[i] - r.path[i - 1]).norm();
      }
      EXPECT_NEAR(drawn, r.travel, 1e-3 * r.travel);
    } else {
      EXPECT_TRUE(r.path.empty());
    }
  }
  EXPECT_GT(last, 0.95);
}

TEST(Objects, TheSameSeedGivesTheSameRunAndItsCoverageGrows) {
  const ExplorationResult one = explore_bunny(false, 4);
  const ExplorationResult two = explore_bunny(false, 4);
  ASSERT_EQ(one.scans.size(), two.scans.size());
  for (std::size_t k = 0; k < one.scans.size(); ++k) {
    EXPECT_EQ(one.scans[k].view, two.scans[k].view);
    EXPECT_EQ(one.scans[k].surface_coverage, two.scans[k].surface_coverage);
  }
  EXPECT_GT(*one.scans.back().surface_coverage, *one.scans.front().surface_coverage + 0.2);
}

}  // namespace
}  // namespace vantage
