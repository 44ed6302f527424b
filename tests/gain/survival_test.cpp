// The survival reading of the visibility (gain/survival.hpp, docs/model.md) on the hand-countable
// row: cells 0-4 free, 5-7 unobserved, 8 occupied, 9-11 unobserved, 12-19 free.

#include "vantage/gain/survival.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "row_grid.hpp"
#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/ray_model.hpp"
#include "vantage/gain/view_gain.hpp"

namespace vantage {
namespace {

using test::looking_along_x;
using test::row_grid;
using test::row_spec;

GainConfig survival(double alpha) {
  GainConfig config;
  config.method = GainMethod::kSurvival;
  config.alpha = alpha;
  config.epsilon = 0.0;
  return config;
}

/// The paper's occupancy filter (eqs. 14, 15, 12) along cells 0 ... target with the given
/// visibilities, written out again from docs/model.md.
double posterior(const OccupancyGrid& grid, const std::vector<double>& v, std::size_t target) {
  double q = grid.probability(0);
  for (std::size_t m = 1; m <= target; ++m) {
    const double tau = 0.5 + v[m] / 2.0;
    const double pred = tau * q + (1.0 - tau) * (1.0 - q);
    const double p = grid.probability(m);
    q = pred * p / (pred * p + (1.0 - pred) * (1.0 - p));
  }
  return q;
}

TEST(Survival, SeesEachUnobservedCellWithAToThePowerOfThoseBeforeIt) {
  const OccupancyGrid grid = row_grid();
  const ViewGain gain = exact_view_gain(grid, looking_along_x({0.05, 0.0, 0.0}), survival(0.9));
  EXPECT_EQ(gain.targets, 6u);
  // Cells 5, 6, 7 behind free space and 0, 1, 2 unobserved cells; 9-11 behind the occupied 8.
  EXPECT_NEAR(gain.cells, 1.0 + 0.9 + 0.81, 1e-12);
  // Bits: eq. (4) with the paper's filter on these visibilities.
  const std::vector<double> v = {1, 1, 1, 1, 1, 1, 0.9, 0.81, 0.729, 0, 0, 0};
  double bits = 0.0;
  for (const std::size_t j : {5, 6, 7, 9, 10, 11}) {
    bits += entropy_bits(grid.probability(j)) - entropy_bits(posterior(grid, v, j));
  }
  EXPECT_NEAR(gain.gain, bits, 1e-12);
  EXPECT_GT(gain.gain, 1.0);
}

TEST(Survival, AtAOfOneItCountsWhatGreedyCounts) {
  const OccupancyGrid grid = row_grid();
  GainConfig greedy;
  greedy.method = GainMethod::kGreedy;
  for (const Eigen::Vector3d& origin :
       {Eigen::Vector3d(0.05, 0, 0), Eigen::Vector3d(-0.95, 0, 0)}) {
    const Frustum view = looking_along_x(origin);
    EXPECT_DOUBLE_EQ(exact_view_gain(grid, view, survival(1.0)).cells,
                     exact_view_gain(grid, view, greedy).cells);
  }
}

TEST(Survival, VisibilityFallsWithEveryUnobservedCellAndStaysInZeroOne) {
  // An all-unknown row entered from 1 m outside: 10 free cells first, then unobserved ones.
  const OccupancyGrid grid(row_spec());
  const Frustum view = looking_along_x({-0.95, 0.0, 0.0});
  double previous = 21.0;
  for (const double alpha : {1.0, 0.99, 0.9, 0.5, 0.01}) {
    const ViewGain gain = exact_view_gain(grid, view, survival(alpha));
    double expected = 0.0;  // target j has j unobserved cells before it
    for (int j = 0; j < 20; ++j) expected += std::pow(alpha, j);
    EXPECT_NEAR(gain.cells, expected, 1e-9) << alpha;
    EXPECT_LT(gain.cells, previous) << alpha;
    EXPECT_GE(gain.gain, 0.0) << alpha;
    previous = gain.cells;
  }
}

TEST(Survival, AutoTakesTheExactEvaluation) {
  const OccupancyGrid grid = row_grid();
  const std::vector<Frustum> views = {looking_along_x({0.05, 0.0, 0.0}),
                                      looking_along_x({-0.95, 0.0, 0.0})};
  GainConfig config = survival(0.95);
  config.evaluation = GainEvaluation::kExact;
  const std::vector<ViewGain> exact = evaluate_views(grid, views, config);
  for (const GainEvaluation e : {GainEvaluation::kAuto}) {
    config.evaluation = e;
    const std::vector<ViewGain> other = evaluate_views(grid, views, config);
    for (std::size_t i = 0; i < views.size(); ++i) {
      EXPECT_EQ(other[i].gain, exact[i].gain);
      EXPECT_EQ(other[i].cells, exact[i].cells);
    }
  }
}

TEST(Survival, OnePassGivesEveryAsExpectedCellsForAnyThreadCount) {
  const OccupancyGrid grid = row_grid();
  const std::vector<Frustum> views = {looking_along_x({0.05, 0.0, 0.0}),
                                      looking_along_x({-0.95, 0.0, 0.0})};
  const std::vector<double> alphas = {0.5, 0.9, 0.99, 1.0};
  const std::vector<double> one = survival_cells_by_alpha(grid, views, alphas, 1);
  ASSERT_EQ(one.size(), alphas.size());
  EXPECT_EQ(survival_cells_by_alpha(grid, views, alphas, 2), one);
  for (std::size_t j = 0; j < alphas.size(); ++j) {
    double expected = 0.0;
    for (const ViewGain& g : exact_view_gains(grid, views, survival(alphas[j])))
      expected += g.cells;
    EXPECT_NEAR(one[j], expected, 1e-12) << alphas[j];
  }
}

}  // namespace
}  // namespace vantage
