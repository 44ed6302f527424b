// The decision's cost estimate and the work budget (issue 39; docs/robustness.md, "Work").

#include "vantage/experiment/decision_cost.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "vantage/util/work.hpp"

namespace vantage {
namespace {

/// A box of 20^3 cells of 5 cm in front of a sensor at the origin looking along +x.
GridSpec box(double resolution = 0.05) {
  const int n = static_cast<int>(std::lround(1.0 / resolution));
  return GridSpec::centered({1.0, 0.0, 0.0}, resolution, {n, n, n});
}

/// A sensor at the origin looking along +x (yaw 180: back, away from the box).
Frustum view(double yaw_deg = 0.0, double fov_deg = 120.0) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() =
      Eigen::AngleAxisd(yaw_deg * std::numbers::pi / 180.0, Eigen::Vector3d::UnitZ()).matrix();
  const double fov = fov_deg * std::numbers::pi / 180.0;
  return Frustum(pose, SensorFov{fov, fov, 0.1, 3.0});
}

std::vector<Eigen::Isometry3d> ring(int n) {
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < n; ++i) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    const double angle = 2.0 * std::numbers::pi * i / n;
    pose.translation() = Eigen::Vector3d(1.0 - 1.5 * std::cos(angle), -1.5 * std::sin(angle), 0.0);
    pose.linear() = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).matrix();
    poses.push_back(pose);
  }
  return poses;
}

PlannerConfig survival() {
  PlannerConfig config;
  config.method = PlannerMethod::kSurvival;
  config.objective = GainObjective::kCells;
  return config;
}

TEST(DecisionCost, AViewThatHoldsTheWholeGridCountsItsCells) {
  // NOTE: the box spans x in [0.5, 1.5] m and y, z in [-0.5, 0.5] m: a 120-degree view from the
  // origin holds all of it. 16 x 12 rays stand for the frustum, so within 15 %.
  const ViewCost cost = view_cost(box(), view(), 32);
  EXPECT_NEAR(cost.cells, 8000.0, 0.15 * 8000.0);
  // Each cell's ray walks from where it enters the box, at most 20 x 3 cells: between the cells
  // and 60 steps a cell.
  EXPECT_GT(cost.exact_steps, cost.cells);
  EXPECT_LT(cost.exact_steps, 61.0 * cost.cells);
}

TEST(DecisionCost, HalvingTheCellsEdgeMultipliesTheWalksBySixteen) {
  const ViewCost coarse = view_cost(box(0.05), view(), 32);
  const ViewCost fine = view_cost(box(0.025), view(), 32);
  EXPECT_NEAR(fine.cells / coarse.cells, 8.0, 0.01);
  // Eight times the targets, each walking twice the cells (less the one cell each counts).
  EXPECT_NEAR(fine.exact_steps / coarse.exact_steps, 16.0, 1.0);
  EXPECT_NEAR(fine.ray_cells / coarse.ray_cells, 2.0, 0.1);
}

TEST(DecisionCost, AViewAwayFromTheGridCostsNothingButItsRays) {
  const ViewCost away = view_cost(box(), view(180.0, 60.0), 32);
  EXPECT_EQ(away.cells, 0.0);
  EXPECT_EQ(away.exact_steps, 0.0);
  EXPECT_GT(away.swept_rays, 0.0);  // the swept search still sets its rays up
}

TEST(DecisionCost, TheEstimateIsLinearInTheViewsAndTheSameEveryTime) {
  const PlannerConfig config = survival();
  const SensorFov fov{1.0, 0.8, 0.1, 3.0};
  const std::vector<Eigen::Isometry3d> poses = ring(1000);
  const DecisionCost once = estimate_decision(box(), poses, fov, config);
  EXPECT_EQ(once.steps, estimate_decision(box(), poses, fov, config).steps);
  EXPECT_NE(once.path.find("swept"), std::string::npos);
  // Ten copies of the ring: ten times the views, the same mean view.
  std::vector<Eigen::Isometry3d> ten;
  for (int k = 0; k < 10; ++k) ten.insert(ten.end(), poses.begin(), poses.end());
  const DecisionCost tenfold = estimate_decision(box(), ten, fov, config);
  EXPECT_EQ(tenfold.views, 10000u);
  // NOTE: the swept search's second and last rounds are a fixed few views, and the sampled views
  // differ, so a little less.
  EXPECT_GT(tenfold.steps / once.steps, 9.0);
  EXPECT_LT(tenfold.steps / once.steps, 10.5);
  // A map with fewer unobserved cells costs less, and no map costs less than none unobserved.
  const DecisionCost half = estimate_decision(box(), poses, fov, config, 0.5);
  const DecisionCost none = estimate_decision(box(), poses, fov, config, 0.0);
  EXPECT_LT(half.steps, once.steps);
  EXPECT_LT(none.steps, half.steps);
  EXPECT_GT(none.steps, 0.0);
}

TEST(DecisionCost, TheBudgetRefusesWithTheEstimateAndTheOption) {
  const std::vector<Eigen::Isometry3d> poses = ring(100);
  const DecisionCost cost = estimate_decision(box(), poses, SensorFov{}, survival());
  WorkBudget budget;
  budget.max_bytes = 1ull << 40;
  budget.max_seconds = 2.0 * cost.seconds();
  EXPECT_NO_THROW(check_decision(cost, budget));
  budget.max_seconds = 0.5 * cost.seconds();
  try {
    check_decision(cost, budget);
    FAIL() << "a decision over its budget passed";
  } catch (const WorkBudgetError& e) {
    const std::string what = e.what();
    EXPECT_FALSE(e.memory);
    EXPECT_NE(what.find("more than --max-work"), std::string::npos) << what;
    EXPECT_NE(what.find("ray-cell steps at 10 ns"), std::string::npos) << what;
    EXPECT_NE(what.find("the swept search over 100 views"), std::string::npos) << what;
  }
  budget.work_option = "max_work";
  EXPECT_THROW(
      {
        try {
          check_decision(cost, budget);
        } catch (const WorkBudgetError& e) {
          EXPECT_NE(std::string(e.what()).find("more than max_work"), std::string::npos);
          throw;
        }
      },
      WorkBudgetError);
}

TEST(DecisionCost, ASequencesShortlistIsWeighedByItsMemory) {
  // issue 39: --method sequence --views 100000 --shortlist 1000000 said "out of memory" after
  // 108 s; its travel table alone is 10^10 doubles.
  PlannerConfig config = survival();
  config.method = PlannerMethod::kSequence;
  config.sequence.shortlist = 1'000'000;
  const std::vector<Eigen::Isometry3d> poses = ring(100'000);
  const DecisionCost cost = estimate_decision(box(), poses, SensorFov{}, config, 0.0);
  EXPECT_GT(cost.bytes, 8e10);  // 10^5 x 10^5 x 8 B
  WorkBudget budget;
  budget.max_bytes = 4ull << 30;
  budget.max_seconds = 1e9;
  try {
    check_decision(cost, budget);
    FAIL() << "a shortlist of 100000 views passed a 4 GiB budget";
  } catch (const WorkBudgetError& e) {
    EXPECT_TRUE(e.memory);
    EXPECT_NE(std::string(e.what()).find("more than --max-memory 4 GiB"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("a smaller shortlist"), std::string::npos) << e.what();
  }
  // The default shortlist of 40 views holds kilobytes of travel.
  config.sequence.shortlist = 40;
  EXPECT_LT(estimate_decision(box(), poses, SensorFov{}, config, 0.0).bytes, 1e9);
}

TEST(DecisionCost, AMetricIsWeighedByWhatItHoldsPerCell) {
  // The surface model (the default around objects) holds a snapshot, a distance and an index a
  // cell beside the grid: on a 62.5 M-cell map, about 750 MB the candidates alone do not show.
  const std::vector<Eigen::Isometry3d> poses = ring(30);
  PlannerConfig surface;
  surface.method = default_planner_method(ViewTask::kObjects, false);
  PlannerConfig area = surface;
  area.method = PlannerMethod{GainMethod::kOcclusionAware};
  const double cells = static_cast<double>(box().num_cells());
  const double plain = estimate_decision(box(), poses, SensorFov{}, survival(), 0.0).bytes;
  EXPECT_GE(estimate_decision(box(), poses, SensorFov{}, surface, 0.0).bytes, plain + 12.0 * cells);
  EXPECT_GE(estimate_decision(box(), poses, SensorFov{}, area, 0.0).bytes, plain + 4.0 * cells);
  EXPECT_LT(estimate_decision(box(), poses, SensorFov{}, area, 0.0).bytes, plain + 12.0 * cells);
}

TEST(DecisionCost, ThePrunedSearchIsWeighedAtItsWorstEveryViewEvaluated) {
  PlannerConfig bits;  // the paper's method by bits: the pruned search
  const std::vector<Eigen::Isometry3d> poses = ring(30);
  const DecisionCost pruned = estimate_decision(box(), poses, SensorFov{}, bits);
  EXPECT_NE(pruned.path.find("pruned"), std::string::npos);
  const ViewCost one = view_cost(box(), Frustum(poses[0], SensorFov{}), bits.swept_rays);
  EXPECT_GE(pruned.steps, 0.5 * 30.0 * one.exact_steps);
  // Nothing unobserved: nothing to evaluate.
  EXPECT_EQ(estimate_decision(box(), poses, SensorFov{}, bits, 0.0).steps, 0.0);
}

TEST(DecisionCost, SecondsAreStepsAtTheMeasuredRate) {
  EXPECT_DOUBLE_EQ(work_seconds(1e9), kNanosecondsPerStep);
  EXPECT_EQ(describe_seconds(86.2), "86.2 s");
  EXPECT_EQ(describe_seconds(1800.0), "30 min");
  EXPECT_EQ(describe_seconds(36000.0), "10 h");
}

// The yardstick's set-up: one scan of every candidate and start, each of the sensor's rays at the
// measured rate; refused past the budget before any is cast, with the estimate and the option.
TEST(DecisionCost, TheYardsticksScansAreWeighedBeforeTheyAreCast) {
  sim::Scene scene;
  scene.sensor.type = sim::SensorType::kRgbd;
  scene.sensor.width = 640;
  scene.sensor.height = 480;
  scene.start_poses.assign(10, Eigen::Isometry3d::Identity());
  EXPECT_EQ(simulated_rays_per_scan(scene.sensor), 307200.0);
  WorkBudget budget;
  budget.max_seconds = 60.0;
  // 1 000 views and 10 starts: 1 010 x 307 200 rays at 100 ns, 31 s.
  EXPECT_NO_THROW(check_surface_truth(scene, 1000, budget));
  // 5 000 views: 154 s.
  try {
    check_surface_truth(scene, 5000, budget);
    ADD_FAILURE() << "5 000 views' scans were allowed";
  } catch (const WorkBudgetError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("5000 candidate views"), std::string::npos) << what;
    EXPECT_NE(what.find("154 s"), std::string::npos) << what;
    EXPECT_NE(what.find("--max-work"), std::string::npos) << what;
    EXPECT_FALSE(e.memory);
  }
  budget.max_seconds = 200.0;
  EXPECT_NO_THROW(check_surface_truth(scene, 5000, budget));
}

}  // namespace
}  // namespace vantage
