// The sequence decision (vantage/planner/sequence.hpp) on the built-in tabletop-4 of vantage::sim,
// after 1 and 3 scans, the ring views not yet taken: with horizon 1 and no travel weight it
// chooses what today's exhaustive exact decision chooses, survival (cells) and greedy; with a
// longer horizon its joint value is that of its views' per-cell visibilities.

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "vantage/gain/snapshot.hpp"
#include "vantage/map/integrate.hpp"
#include "vantage/planner/observability.hpp"
#include "vantage/planner/planner.hpp"
#include "vantage/planner/sequence.hpp"
#include "vantage/sim/world.hpp"

namespace vantage {
namespace {

TEST(SequenceScenes, HorizonOneIsTodaysDecisionOnTabletop4) {
  const sim::World world(sim::load_scene("tabletop-4"));
  const sim::Scene& scene = world.scene();
  OccupancyGrid grid(scene.grid);
  std::vector<Eigen::Isometry3d> taken;
  constexpr int kOrder[3] = {0, 5, 2};
  for (int k = 0; k < 3; ++k) {
    const Eigen::Isometry3d& pose = scene.start_poses[static_cast<std::size_t>(kOrder[k])];
    const sim::SimulatedScan scan = world.scan(pose, 1000 + k);
    integrate_scan(grid, Scan{scan.points_world(), scan.view()}, IntegrationConfig{});
    taken.push_back(pose);
    if (k == 1) continue;
    std::vector<Candidate> ring;
    std::vector<Frustum> views;
    std::vector<double> travel;
    for (const Eigen::Isometry3d& c : scene.candidate_poses()) {
      if (std::any_of(taken.begin(), taken.end(), [&](const auto& t) { return t.isApprox(c); })) {
        continue;
      }
      ring.push_back({Frustum(c, scene.fov()), (c.translation() - pose.translation()).norm()});
      views.push_back(ring.back().view);
      travel.push_back(ring.back().travel);
    }
    for (const PlannerMethod method : {PlannerMethod::kSurvival, PlannerMethod::kGreedy}) {
      PlannerConfig today;
      today.method = method;
      today.objective = GainObjective::kCells;
      today.gain.method = method.gain;
      today.gain.alpha = kSurvivalAlpha;
      today.gain.evaluation = GainEvaluation::kExact;
      today.search = DecisionSearch::kExhaustive;
      const Plan plan = plan_next_view(grid, ring, today);
      const SequencePlan one = plan_sequence(grid, views, travel, today.gain, SequenceConfig{});
      EXPECT_EQ(one.first, plan.best) << to_string(method) << " after " << k + 1 << " scans";
      for (std::size_t c = 0; c < ring.size(); ++c) {
        EXPECT_EQ(one.gains[c].cells, plan.scores[c]) << "candidate " << c;
      }
      SequenceConfig three;
      three.horizon = 3;
      three.shortlist = 8;
      const SequencePlan seq = plan_sequence(grid, views, travel, today.gain, three);
      ASSERT_EQ(seq.chosen.size(), 3u);
      EXPECT_EQ(seq.chosen.front(), plan.best);  // the first pick is the best single view
      const std::vector<ViewCells> lists = exact_view_cells(
          ClassMap(grid),
          std::vector<Frustum>{views[seq.chosen[0]], views[seq.chosen[1]], views[seq.chosen[2]]},
          today.gain);
      const std::vector<const ViewCells*> set = {&lists[0], &lists[1], &lists[2]};
      EXPECT_NEAR(seq.value, joint_cells(set), 1e-6 * seq.value);
      EXPECT_LT(seq.value, lists[0].sum() + lists[1].sum() + lists[2].sum());
    }
  }
}

}  // namespace
}  // namespace vantage
