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

#include "tests/planner/oracle_states.hpp"
#include "vantage/planner/choose.hpp"
#include "vantage/planner/planner.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

using oracle::Reference;

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
  oracle::for_each_state(
      world, name,
      [&](const std::string& state, const OccupancyGrid& grid, const std::vector<Candidate>& ring,
          int scans, const Eigen::Isometry3d& pose) {
        const Reference reference = oracle::reference_of(grid, ring);
        check_state(state, grid, ring, reference, PlannerMethod::kSurvival, scans == 1);
        check_state(state, grid, ring, reference, PlannerMethod::kGreedy);
        check_state(state, grid, ring, reference, PlannerMethod::kLatombe);
        if (scans == 1 && name == "tabletop-4") {
          const std::vector<Candidate> views =
              oracle::sphere_candidates(world.scene(), 200, pose.translation());
          const Reference sphere_reference = oracle::reference_of(grid, views);
          for (const PlannerMethod m :
               {PlannerMethod::kSurvival, PlannerMethod::kGreedy, PlannerMethod::kLatombe}) {
            check_state(cat(name, " after 1 scan, 200-view sphere"), grid, views, sphere_reference,
                        m);
          }
        }
      });
}

INSTANTIATE_TEST_SUITE_P(BuiltInTableTops, SweptDecision,
                         ::testing::Values("tabletop-1", "tabletop-2", "tabletop-3", "tabletop-4"));

}  // namespace
}  // namespace vantage
