// docs/architecture.md's worked examples, compiled and held to what they claim: a model in one
// file (examples/architecture/frontier_voxel.hpp) and a search in one file
// (examples/architecture/exact_search.cpp) and a candidate set in one file
// (examples/architecture/cube_views.cpp), each run through the interface its registry row
// would list it by.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "examples/architecture/cube_views.cpp"    // NOLINT: the example is one file
#include "examples/architecture/exact_search.cpp"  // NOLINT: the example is one file
#include "examples/architecture/frontier_voxel.hpp"
#include "tests/planner/views_around.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/gain/models/metric_rays.hpp"
#include "vantage/gain/models/metrics/unobserved_voxel.hpp"
#include "vantage/planner/planner.hpp"

namespace vantage {
namespace {

// A block whose -x half is known free and whose +x half is unobserved, with views around it.
struct HalfFreeBlock {
  OccupancyGrid grid{GridSpec::centered({0, 0, 0}, 0.05, {20, 20, 10})};
  std::vector<Candidate> candidates;
  HalfFreeBlock() {
    for (std::size_t i = 0; i < grid.size(); ++i) {
      if (grid.spec().unravel(i).x() < 10) grid.miss(i);
    }
    candidates = test::views_around_block();
  }
};

TEST(WorkedExamples, AModelInOneFileEvaluatesThroughTheMetricsRays) {
  const HalfFreeBlock s;
  const GainMap map(s.grid, 1);
  const std::vector<float> no_distances;
  const detail::MetricContext ctx{map, no_distances, 0.7071, 1};
  std::vector<Frustum> views;
  for (const Candidate& c : s.candidates) views.push_back(c.view);
  const std::vector<ViewGain> frontier = detail::all_views<FrontierVoxel>(ctx, views, 1);
  const std::vector<ViewGain> unobserved = detail::all_views<UnobservedVoxel>(ctx, views, 1);
  // From -x (k = 2) the rays cross the free half first: they meet the frontier. From +x (k = 0)
  // they enter the unobserved half from outside the grid: no free cell before any of them.
  EXPECT_GT(frontier[2].gain, 0.0);
  EXPECT_EQ(frontier[0].gain, 0.0);
  for (std::size_t v = 0; v < views.size(); ++v) {
    EXPECT_LE(frontier[v].gain, unobserved[v].gain) << "view " << v;
    EXPECT_EQ(frontier[v].gain, std::round(frontier[v].gain)) << "view " << v;
  }
  // A frontier cell is one cell beyond the free half: at most the 20 x 10 cells of that layer.
  EXPECT_LE(frontier[2].gain, 200.0);
}

TEST(WorkedExamples, ASearchInOneFileDecidesBehindTheInterface) {
  const HalfFreeBlock s;
  for (const PlannerMethod method : {PlannerMethod::kGreedy, PlannerMethod::kLatombe}) {
    PlannerConfig config;
    config.method = method;
    config.gain.evaluation = GainEvaluation::kExact;
    ASSERT_TRUE(kExactSearch.serves(config));
    config.search = DecisionSearch::kExhaustive;
    const Plan reference = plan_next_view(s.grid, s.candidates, config);
    const CandidateViews views(s.candidates);
    GainConfig gain = config.gain;
    gain.method = method.gain;
    const Plan plan = kExactSearch.run(SearchInput{s.grid, s.candidates, views, config, gain,
                                                   std::chrono::steady_clock::now(), 0});
    EXPECT_EQ(plan.search, DecisionSearch{"exact"});
    EXPECT_EQ(plan.best, reference.best) << to_string(method);
    EXPECT_EQ(plan.scores, reference.scores) << to_string(method);
    EXPECT_EQ(plan.greedy_gains, reference.greedy_gains) << to_string(method);
  }
  PlannerConfig survival;
  survival.method = PlannerMethod::kSurvival;
  EXPECT_FALSE(kExactSearch.serves(survival));
  // Not registered: naming it is refused, as any unknown search is.
  EXPECT_THROW((void)parse_decision_search("exact"), std::invalid_argument);
}

TEST(WorkedExamples, ACandidateSetInOneFileBuildsThroughItsRow) {
  CandidateSite site;
  site.target = {0.2, 0.1, 0.9};
  site.region = Eigen::AlignedBox3d(site.target - Eigen::Vector3d::Constant(0.4),
                                    site.target + Eigen::Vector3d::Constant(0.4));
  const PlacedViews views = kCubeRow.build(site, CandidateParams{});
  ASSERT_EQ(views.poses.size(), 6u);
  for (const Eigen::Isometry3d& pose : views.poses) {
    EXPECT_NEAR((pose.translation() - site.target).norm(), 0.5, 1e-12);
    EXPECT_NEAR(pose.linear().col(0).dot((site.target - pose.translation()).normalized()), 1.0,
                1e-12);
  }
  EXPECT_EQ(views.travel.kind, TravelRule::Kind::kStraightLine);
  // Not in the registry until its row is added: the example does not change the library.
  EXPECT_FALSE(is_candidate_set(kCubeRow.name));
}

}  // namespace
}  // namespace vantage
