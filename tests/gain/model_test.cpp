// The one ray model (vantage/gain/model.hpp): PaperModel::step against its readable twin
// RayModel, the tables built from it, and that both evaluation modes follow the model they are
// given (BlindModel, which sees nothing, must make both predict nothing).

#include "vantage/gain/model.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "bench/synthetic_tabletop.hpp"
#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/ray_model.hpp"

namespace vantage {
namespace {

TEST(PaperModel, MatchesRayModelAlongRandomRays) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> any(0.01, 0.99);
  const OccupancyParams params;
  const double levels[] = {params.p_min, 0.4, 0.5, 0.7, params.p_max};
  std::uniform_int_distribution<int> level(0, 5);
  // NOTE: not alpha = 1, where v stays 1 and q becomes a bare product of likelihood ratios: the
  // direct form keeps q near 1 as a double and loses 1 - q, which the odds form keeps.
  for (const double alpha : {0.997, 0.9999, 0.99999, 0.9}) {
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<double> p(300);
      for (double& x : p) {
        const int k = level(rng);
        x = k < 5 ? levels[k] : any(rng);
      }
      const std::vector<RayState> states = RayModel(alpha).trace(p);
      const RayTables<PaperModel> tables(alpha, params.p_min, 300);
      RayOdds odds = PaperModel::start(p[0]);
      for (int m = 1; m < 300; ++m) {
        const auto i = static_cast<std::size_t>(m);
        tables.step(odds, m, p[i - 1], p[i]);
        ASSERT_NEAR(odds.visibility(), states[i].visibility, 1e-12) << "alpha " << alpha;
        ASSERT_NEAR(odds.posterior(), states[i].posterior, 1e-12) << "alpha " << alpha;
      }
    }
  }
}

TEST(PaperModel, TablesHoldTheFreeCellsBeforeTheGrid) {
  const double alpha = 0.997, p_min = 0.12;
  const RayTables<PaperModel> tables(alpha, p_min, 60);
  ASSERT_EQ(tables.t.size(), 61u);
  ASSERT_EQ(tables.outside.size(), 61u);
  EXPECT_EQ(tables.t[0], 1.0);
  EXPECT_NEAR(tables.t[60], std::pow(alpha, 60), 1e-14);
  // outside[k] is the state after k free cells; entering at c_k with p is one more step.
  std::vector<double> ray(41, p_min);
  ray.push_back(0.5);
  const std::vector<RayState> states = RayModel(alpha).trace(ray);
  EXPECT_NEAR(tables.outside[41].visibility(), states[40].visibility, 1e-12);
  EXPECT_NEAR(tables.outside[41].posterior(), states[40].posterior, 1e-12);
  const RayOdds in = tables.enter(41, 0.5);
  EXPECT_NEAR(in.visibility(), states[41].visibility, 1e-12);
  EXPECT_NEAR(in.posterior(), states[41].posterior, 1e-12);
  EXPECT_EQ(tables.enter(0, 0.3).visibility(), 1.0);  // the origin's own cell
  EXPECT_EQ(tables.enter(0, 0.3).posterior(), 0.3);
}

TEST(RayOdds, StopTestsMatchTheirDefinitions) {
  const RayOdds hidden(0.0004, 0.5);
  EXPECT_TRUE(hidden.hidden(1e-3));
  EXPECT_FALSE(hidden.hidden(1e-4));
  const RayOdds pinned(0.5, 0.5005);
  EXPECT_TRUE(pinned.pinned(1e-3));
  EXPECT_FALSE(pinned.pinned(1e-4));
  EXPECT_FALSE(pinned.hidden(0.0));
  EXPECT_FALSE(RayOdds(0.5, 0.5).pinned(0.0));  // epsilon 0 never stops
}

TEST(BlindModel, SeesNothingAfterTheOrigin) {
  const RayTables<BlindModel> tables(0.997, 0.12, 20);
  RayOdds s = tables.enter(5, 0.5);
  EXPECT_EQ(s.visibility(), 0.0);
  EXPECT_EQ(s.posterior(), 0.5);
  tables.step(s, 6, 0.5, 0.97);
  EXPECT_EQ(s.visibility(), 0.0);
  EXPECT_DOUBLE_EQ(s.posterior(), 0.97);
}

// Changing the model changes the evaluation: with the paper's model it predicts a gain on a table
// top after one scan; with a model that sees nothing, nothing, over the same target cells.
TEST(ExactEvaluation, FollowsTheModelItIsGiven) {
  const OccupancyGrid grid =
      synthetic::map_after(synthetic::table_top(0), synthetic::grid_spec(), 1, 160, 120);
  const std::vector<Frustum> ring = synthetic::ring_views();
  const std::vector<Frustum> views(ring.begin(), ring.begin() + 6);
  const GainMap map(grid, 2);
  GainConfig config;
  config.epsilon = 0.0;  // the literal model
  const auto paper_exact = exact_view_gains<PaperModel>(map, views, config);
  const auto blind_exact = exact_view_gains<BlindModel>(map, views, config);
  for (std::size_t v = 0; v < views.size(); ++v) {
    ASSERT_GT(paper_exact[v].targets, 1000u) << "view " << v;
    EXPECT_GT(paper_exact[v].gain, 1.0) << "view " << v;
    EXPECT_EQ(blind_exact[v].targets, paper_exact[v].targets) << "view " << v;
    // H(p) - H(q) with q = p up to the rounding of a / (a + b).
    EXPECT_NEAR(blind_exact[v].gain, 0.0, 1e-9) << "view " << v;
    // In cells the same: the paper's model sees some, the blind one none.
    EXPECT_GT(paper_exact[v].cells, 10.0) << "view " << v;
    EXPECT_EQ(blind_exact[v].cells, 0.0) << "view " << v;
  }
  // The public entry points run the paper's model.
  const auto plain = exact_view_gains(grid, views, config);
  for (std::size_t v = 0; v < views.size(); ++v) EXPECT_EQ(plain[v].gain, paper_exact[v].gain);
}

}  // namespace
}  // namespace vantage
