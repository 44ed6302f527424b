// The oracle of the swept decision (PlannerConfig::search = kSwept, docs/decision.md) on the
// built-in table tops of vantage::sim: after 1, 3 and 6 paper-mode scans with the ring views not
// yet taken, and on tabletop-4 after one scan a 200-view sphere. The search is statistical, so
// the oracle is what it measures: its choice must be the exhaustive exact search's in every
// state, for the survival reading (cells), greedy and Latombe; the chosen candidate's reported
// gain is its full evaluation; 1 and 2 threads decide alike.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "vantage/gain/hierarchy.hpp"
#include "vantage/gain/swept.hpp"
#include "vantage/map/integrate.hpp"
#include "vantage/planner/choose.hpp"
#include "vantage/planner/observability.hpp"
#include "vantage/planner/planner.hpp"
#include "vantage/sim/world.hpp"
#include "vantage/util/text.hpp"
#include "vantage/views/sphere.hpp"

namespace vantage {
namespace {

constexpr int kOrder[6] = {0, 5, 2, 7, 3, 8};

/// Every candidate's exact sums: the survival reading's cells and greedy's count, by the
/// evaluation the exhaustive exact search's sums equal bit for bit (hierarchy_test.cpp).
struct Reference {
  std::vector<ViewGain> survival, greedy;
};

Reference reference_of(const OccupancyGrid& grid, const std::vector<Candidate>& cands) {
  std::vector<Frustum> views;
  for (const Candidate& c : cands) views.push_back(c.view);
  const GainMap map(grid, 0);
  const ClassBlocks blocks = summarize_classes(map, views, 0);
  GainConfig gain;
  gain.alpha = kSurvivalAlpha;
  gain.method = GainMethod::kSurvival;
  Reference r;
  r.survival = count_view_gains(map, &blocks, views, CountRule::kSurvivalCells, gain);
  gain.method = GainMethod::kGreedy;
  r.greedy = count_view_gains(map, &blocks, views, CountRule::kGreedy, gain);
  return r;
}

void check_state(const std::string& state, const OccupancyGrid& grid,
                 const std::vector<Candidate>& cands, const Reference& reference,
                 PlannerMethod method, bool two_threads = false) {
  PlannerConfig config;
  config.method = method;
  config.objective = GainObjective::kCells;
  config.gain.alpha = method == PlannerMethod::kSurvival ? kSurvivalAlpha : kTableTopAlpha;
  config.search = DecisionSearch::kSwept;
  config.gain.num_threads = 1;
  std::vector<double> exact;
  for (std::size_t c = 0; c < cands.size(); ++c) {
    const double factor =
        method == PlannerMethod::kLatombe ? std::exp(-config.lambda * cands[c].travel) : 1.0;
    exact.push_back(method == PlannerMethod::kSurvival ? reference.survival[c].cells
                                                       : reference.greedy[c].gain * factor);
  }
  const std::size_t best = choose_best(exact);
  const Plan plan = plan_next_view(grid, cands, config);
  const std::string what = cat(state, ", ", to_string(method));
  ASSERT_EQ(plan.scores.size(), cands.size()) << what;
  EXPECT_EQ(plan.best, best) << what << ": chose a view of " << exact[plan.best] / exact[best]
                             << " of the best's exact score";
  EXPECT_FALSE(plan.estimated[plan.best]) << what;
  const ViewGain& full = method == PlannerMethod::kSurvival ? reference.survival[plan.best]
                                                            : reference.greedy[plan.best];
  EXPECT_EQ(plan.gains[plan.best].cells, full.cells) << what;
  EXPECT_LE(plan.evaluated, 3u) << what;
  std::printf("%s: chose %zu (best %zu) of %zu\n", what.c_str(), plan.best, best, cands.size());
  if (!two_threads) return;
  config.gain.num_threads = 2;
  const Plan two = plan_next_view(grid, cands, config);
  EXPECT_EQ(two.best, plan.best) << what;
  EXPECT_EQ(two.scores, plan.scores) << what;
}

class SweptDecision : public ::testing::TestWithParam<const char*> {};

TEST_P(SweptDecision, ChoosesWhatExhaustiveExactSearchChooses) {
  const std::string name = GetParam();
  const sim::World world(sim::load_scene(name));
  const sim::Scene& scene = world.scene();
  OccupancyGrid grid(scene.grid);
  std::vector<Eigen::Isometry3d> taken;
  for (int k = 0; k < 6; ++k) {
    const Eigen::Isometry3d& pose = scene.start_poses[static_cast<std::size_t>(kOrder[k])];
    const sim::SimulatedScan scan = world.scan(pose, 1000 + k);
    integrate_scan(grid, Scan{scan.points_world(), scan.view()}, IntegrationConfig{});
    taken.push_back(pose);
    if (k != 0 && k != 2 && k != 5) continue;
    const Eigen::Vector3d here = pose.translation();
    std::vector<Candidate> ring;
    for (const Eigen::Isometry3d& c : scene.candidate_poses()) {
      const bool was_taken = std::any_of(taken.begin(), taken.end(),
                                         [&](const auto& t) { return t.isApprox(c, 1e-9); });
      if (!was_taken) ring.push_back({Frustum(c, scene.fov()), (c.translation() - here).norm()});
    }
    const std::string state = cat(name, " after ", k + 1, " scans, ring");
    const Reference reference = reference_of(grid, ring);
    check_state(state, grid, ring, reference, PlannerMethod::kSurvival, k == 0);
    check_state(state, grid, ring, reference, PlannerMethod::kGreedy);
    check_state(state, grid, ring, reference, PlannerMethod::kLatombe);
    if (k == 0 && name == "tabletop-4") {
      SphereConfig sphere;
      sphere.center = scene.ring.center;
      sphere.radius = scene.ring.radius;
      sphere.views = 200;
      std::vector<Candidate> views;
      for (const Eigen::Isometry3d& p : sphere_poses(sphere)) {
        views.push_back({Frustum(p, scene.fov()), (p.translation() - here).norm()});
      }
      const Reference sphere_reference = reference_of(grid, views);
      for (const PlannerMethod m :
           {PlannerMethod::kSurvival, PlannerMethod::kGreedy, PlannerMethod::kLatombe}) {
        check_state(cat(name, " after 1 scan, 200-view sphere"), grid, views, sphere_reference, m);
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(BuiltInTableTops, SweptDecision,
                         ::testing::Values("tabletop-1", "tabletop-2", "tabletop-3", "tabletop-4"));

}  // namespace
}  // namespace vantage
