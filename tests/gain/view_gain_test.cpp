// Exact view gain on grids where the answer can be counted by hand.

#include "vantage/gain/view_gain.hpp"

#include <gtest/gtest.h>

#include <random>

#include "row_grid.hpp"
#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/ray_model.hpp"

namespace vantage {
namespace {

using test::looking_along_x;
using test::row_grid;
using test::row_spec;

TEST(ExactGain, GreedyCountsUnobservedCellsBeforeTheFirstOccupied) {
  const OccupancyGrid grid = row_grid();
  GainConfig config;
  config.method = GainMethod::kGreedy;
  const ViewGain gain = exact_view_gain(grid, looking_along_x({0.05, 0.0, 0.0}), config);
  EXPECT_EQ(gain.targets, 6u);        // cells 5, 6, 7, 9, 10, 11
  EXPECT_DOUBLE_EQ(gain.gain, 3.0);   // 5, 6, 7; the occupied cell 8 hides 9-11
  EXPECT_DOUBLE_EQ(gain.cells, 3.0);  // greedy's cells are its count
}

TEST(ExactGain, ProbabilisticIsTheSumOfRayModelGains) {
  const OccupancyGrid grid = row_grid();
  const double alpha = 0.997;
  // From inside cell 0, the ray to target j passes exactly cells 0 … j of the row.
  std::vector<double> p;
  for (std::size_t i = 0; i < 20; ++i) p.push_back(grid.probability(i));
  const auto states = RayModel(alpha).trace(p);
  double expected = 0.0, seen = 0.0;
  for (const std::size_t j : {5, 6, 7, 9, 10, 11}) {
    expected += states[j].gain();
    seen += states[j].visibility;  // E: v_M of each target (docs/model.md)
  }
  GainConfig config;
  config.alpha = alpha;
  config.epsilon = 0.0;  // the literal model, no early stop
  const ViewGain gain = exact_view_gain(grid, looking_along_x({0.05, 0.0, 0.0}), config);
  EXPECT_EQ(gain.targets, 6u);
  EXPECT_NEAR(gain.gain, expected, 1e-12);
  EXPECT_GT(gain.gain, 2.0);  // the three visible cells carry most of a bit each
  EXPECT_LT(gain.gain, 3.0);  // the three hidden ones almost nothing
  EXPECT_NEAR(gain.cells, seen, 1e-12);
  // By hand (docs/model.md's recursion): cells 5-7 behind free space are seen with v = 0.998,
  // 0.980, 0.962; behind the occupied cell 8 visibility falls to 0.271 and climbs back through the
  // unobserved cells (eq. 9's 0.1 way back) to 0.336 and 0.392, not to 0: E = 3.938 cells.
  EXPECT_NEAR(gain.cells, 3.938, 1e-3);
  for (const std::size_t j : {5, 6, 7}) EXPECT_GT(states[j].visibility, 0.95) << j;
  for (const std::size_t j : {9, 10, 11}) EXPECT_LT(states[j].visibility, 0.4) << j;
}

TEST(ExactGain, CellsOutsideTheGridCountAsFree) {
  // An all-unknown row entered from 1 m outside: the ray crosses 10 free cells first (p_min).
  const OccupancyGrid grid(row_spec());
  const Eigen::Vector3d origin(-0.95, 0.0, 0.0);
  GainConfig config;
  config.alpha = 0.997;
  const double g0 = exact_cell_gain(grid, origin, {0, 0, 0}, config);
  std::vector<double> p(10, grid.params().p_min);
  p.push_back(0.5);
  EXPECT_NEAR(g0, RayModel(0.997).trace(p).back().gain(), 1e-12);
  EXPECT_GT(g0, 0.5);  // a real prediction of gain, not the 0 of a filter started at 0.5
  const ViewGain view = exact_view_gain(grid, looking_along_x(origin), config);
  EXPECT_EQ(view.targets, 20u);
  EXPECT_GT(view.gain, g0);
  // E: the first unknown cell behind 10 free ones is seen with v_10, and every cell is seen with
  // at least the 0.1 / 1.1 of eq. (9)'s way back, at most once.
  EXPECT_GT(view.cells, 20.0 * 0.09);
  EXPECT_LT(view.cells, 20.0);
}

TEST(ExactGain, KnownCellsAndCellsOutsideTheFrustumContributeNothing) {
  OccupancyGrid grid(row_spec());
  for (std::size_t i = 0; i < 20; ++i) grid.miss(i);
  EXPECT_EQ(exact_view_gain(grid, looking_along_x({0.05, 0, 0}), GainConfig{}).targets, 0u);
  // Looking away from the row.
  const OccupancyGrid unknown(row_spec());
  Eigen::Isometry3d away = Eigen::Isometry3d::Identity();
  away.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  away.translation() = Eigen::Vector3d(-0.5, 0, 0);
  EXPECT_EQ(exact_view_gain(unknown, Frustum(away, SensorFov{}), GainConfig{}).targets, 0u);
}

TEST(ExactGain, SameResultForAnyThreadCount) {
  OccupancyGrid grid(GridSpec::centered({0, 0, 0.25}, 0.02, {40, 40, 25}));
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> kind(0, 9);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const int k = kind(rng);
    if (k < 4) grid.miss(i);
    if (k == 9) grid.hit(i);
  }
  std::vector<Frustum> views;
  for (int k = 0; k < 4; ++k) {
    const double a = k * M_PI / 2;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(1.2 * std::cos(a), 1.2 * std::sin(a), 0.6);
    pose.linear() = Eigen::AngleAxisd(a + M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    views.emplace_back(pose, SensorFov{deg2rad(60), deg2rad(45), 0.3, 3.0});
  }
  for (const GainMethod method : {GainMethod::kProbabilistic, GainMethod::kGreedy}) {
    GainConfig one;
    one.method = method;
    one.num_threads = 1;
    GainConfig two = one;
    two.num_threads = 2;
    const auto a = exact_view_gains(grid, views, one);
    const auto b = exact_view_gains(grid, views, two);
    for (std::size_t v = 0; v < views.size(); ++v) {
      EXPECT_EQ(a[v].gain, b[v].gain);  // bitwise
      EXPECT_EQ(a[v].cells, b[v].cells);
      EXPECT_EQ(a[v].targets, b[v].targets);
      EXPECT_GT(a[v].targets, 0u);
    }
  }
}

TEST(GainConfig, RejectsBadValues) {
  GainConfig config;
  config.alpha = 0.0;
  EXPECT_THROW(config.validate(), std::invalid_argument);
  config.alpha = 0.997;
  config.num_threads = -1;
  EXPECT_THROW(config.validate(), std::invalid_argument);
  EXPECT_THROW(parse_gain_method("fancy"), std::invalid_argument);
  EXPECT_EQ(parse_gain_method("greedy"), GainMethod::kGreedy);
}

}  // namespace
}  // namespace vantage
