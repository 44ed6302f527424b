// The swept search's last round (vantage/planner/race.hpp) against the exact sums: on the full
// lists it is the exact argmax with the exact scores, for the survival reading and the paper's
// model; from a sample it drops a clearly worse finalist early and still names the best; the
// same for any thread count; with a tolerance, two views that nearly tie end it before the full
// lists, with a winner within the tolerance.

#include "vantage/planner/searches/race.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/evaluators/hierarchy.hpp"
#include "vantage/gain/evaluators/view_cells.hpp"
#include "vantage/planner/choose.hpp"

namespace vantage {
namespace {

/// A 1.6 m cube of 2 cm cells, unobserved, with an occupied slab that hides part of it from -x.
OccupancyGrid slab_grid() {
  GridSpec spec;
  spec.origin = {-0.8, -0.8, -0.8};
  spec.resolution = 0.02;
  spec.dims = {80, 80, 80};
  OccupancyGrid grid(spec);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const Eigen::Vector3d c = spec.center(spec.unravel(i));
    if (c.x() < -0.5) grid.set_probability(i, 0.12);
    if (std::abs(c.x() + 0.2) < 0.03 && c.y() < 0.1) grid.set_probability(i, 0.97);
  }
  return grid;
}

Frustum view_from(double y) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(-0.75, y, 0.0);
  return Frustum(pose, SensorFov{deg2rad(50), deg2rad(40), 0.1, 2.0});
}

TEST(Race, OnTheFullListsItIsTheExactArgmax) {
  constexpr std::size_t kAll = std::numeric_limits<std::size_t>::max();  // the full lists at once
  const OccupancyGrid grid = slab_grid();
  const GainMap map(grid, 1);
  const ClassMap classes(grid);
  const std::vector<Frustum> views{view_from(-0.4), view_from(0.0), view_from(0.3),
                                   view_from(0.35)};
  const std::vector<std::size_t> first{0, 1, 2, 4};  // the last candidate holds two views
  const std::vector<double> factor{1.0, 0.9, 0.5};
  GainConfig gain;
  gain.method = GainMethod::kSurvival;
  gain.alpha = 0.99;
  gain.num_threads = 1;
  const std::vector<ViewGain> exact =
      count_view_gains(map, nullptr, views, GainQuantity::kSurvivalCells, gain);
  const std::vector<double> scores{exact[0].cells * factor[0], exact[1].cells * factor[1],
                                   (exact[2].cells + exact[3].cells) * factor[2]};
  const detail::Race race = detail::race_candidates(classes, views, first, factor, gain, kAll);
  EXPECT_TRUE(race.exact);
  EXPECT_EQ(race.winner, choose_best(scores));
  for (std::size_t k = 0; k < scores.size(); ++k)
    EXPECT_NEAR(race.scores[k], scores[k], 1e-9 * scores[k]) << k;
  // From a sample of about 6 300 of the 405 000 unobserved cells (one in 64): the hidden view
  // (-0.4) is far behind and drops out before the full lists.
  const detail::Race sampled = detail::race_candidates(classes, views, first, factor, gain, 8192);
  EXPECT_EQ(sampled.winner, choose_best(scores));
  EXPECT_GT(sampled.bits, 0);
  gain.num_threads = 2;
  const detail::Race two = detail::race_candidates(classes, views, first, factor, gain, 8192);
  EXPECT_EQ(two.winner, sampled.winner);
  EXPECT_EQ(two.scores, sampled.scores);
}

// Two views 3 mm apart see nearly the same cells: without a tolerance the race must go to the full
// lists to tell them apart; with 0.5 % it stops on a sample, and its winner is within 0.5 % of the
// best.
TEST(Race, AToleranceEndsANearTieOnASample) {
  const OccupancyGrid grid = slab_grid();
  const GainMap map(grid, 1);
  const ClassMap classes(grid);
  const std::vector<Frustum> views{view_from(0.300), view_from(0.303)};
  const std::vector<std::size_t> first{0, 1, 2};
  const std::vector<double> factor{1.0, 1.0};
  GainConfig gain;
  gain.method = GainMethod::kSurvival;
  gain.alpha = 0.99;
  gain.num_threads = 1;
  const std::vector<ViewGain> exact =
      count_view_gains(map, nullptr, views, GainQuantity::kSurvivalCells, gain);
  const double best = std::max(exact[0].cells, exact[1].cells);
  ASSERT_LT(std::abs(exact[0].cells - exact[1].cells), 0.005 * best);  // a near tie
  const detail::Race strict = detail::race_candidates(classes, views, first, factor, gain, 512);
  const detail::Race loose =
      detail::race_candidates(classes, views, first, factor, gain, 512, 0.005);
  std::printf("strict: %d bits, exact %d; loose: %d bits\n", strict.bits, strict.exact, loose.bits);
  EXPECT_GT(loose.bits, strict.bits);
  EXPECT_GE(exact[loose.winner].cells, (1.0 - 0.005) * best);
}

// Samples boosted by cell (cells_by_sample): a cell of boost o is in the sample of b bits exactly
// when its hash's top max(0, b - o) bits are zero, each sample holds the next smaller, and the
// smallest is the first expected to hold at most the size asked for.
TEST(Race, BoostedSamplesHoldACellOfBoostOBitsEarly) {
  const OccupancyGrid grid = slab_grid();
  std::vector<std::uint32_t> cells;
  std::vector<std::uint8_t> boost(grid.size(), 0);
  for (std::uint32_t i = 0; i < grid.size(); i += 3) {
    cells.push_back(i);
    boost[i] = static_cast<std::uint8_t>(i % 4);
  }
  const std::vector<std::vector<std::uint32_t>> levels = cells_by_sample(cells, 2000, boost);
  const int smallest = static_cast<int>(levels.size()) - 1;
  ASSERT_GT(smallest, 3);
  double expected = 0.0;
  for (const std::uint32_t i : cells)
    expected += std::ldexp(1.0, -std::max(0, smallest - boost[i]));
  EXPECT_LE(expected, 2000.0);
  for (int b = 0; b <= smallest; ++b) {
    std::vector<std::uint32_t> sample, want;
    for (int k = b; k <= smallest; ++k) {
      sample.insert(sample.end(), levels[k].begin(), levels[k].end());
    }
    std::sort(sample.begin(), sample.end());
    for (const std::uint32_t i : cells) {
      if (in_cell_sample(i, std::max(0, b - boost[i]))) want.push_back(i);
    }
    EXPECT_EQ(sample, want) << b;
  }
}

// The survival reading raced on samples boosted by cell, the far side of the slab's shadow sampled
// 8 times as often: on the full lists the exact sums; from a sample the same winner; stopped before
// a sample expected to add more than 5 000 targets to each view's lists, it leaves the two
// near-tied views to the caller.
TEST(Race, RulesBoostStopAndUnseen) {
  constexpr std::size_t kAll = std::numeric_limits<std::size_t>::max();
  const OccupancyGrid grid = slab_grid();
  const GainMap map(grid, 1);
  const ClassMap classes(grid);
  const std::vector<Frustum> views{view_from(-0.4), view_from(0.300), view_from(0.303)};
  const std::vector<std::size_t> first{0, 1, 2, 3};
  const std::vector<double> factor{1.0, 1.0, 1.0};
  GainConfig gain;
  gain.method = GainMethod::kSurvival;
  gain.alpha = 0.99;
  gain.num_threads = 1;
  const std::vector<ViewGain> exact =
      count_view_gains(map, nullptr, views, GainQuantity::kSurvivalCells, gain);
  const std::vector<double> scores{exact[0].cells, exact[1].cells, exact[2].cells};
  std::vector<std::uint32_t> unobserved;
  std::vector<std::uint8_t> boost(grid.size(), 0);
  for (std::uint32_t i = 0; i < grid.size(); ++i) {
    if (classes.state(i) != CellState::kUnobserved) continue;
    unobserved.push_back(i);
    if (grid.spec().center(grid.spec().unravel(i)).x() > 0.0) boost[i] = 3;
  }
  const detail::TargetLister list = [&](std::span<const Frustum> raced,
                                        std::span<const std::size_t>,
                                        std::span<const std::uint32_t> cells) {
    return exact_view_cells(classes, raced, gain, cells);
  };
  const detail::Race full = detail::race_candidates(cells_by_sample(unobserved, kAll, boost), views,
                                                    first, factor, list, {.boost = boost});
  EXPECT_TRUE(full.exact);
  for (std::size_t k = 0; k < scores.size(); ++k)
    EXPECT_NEAR(full.scores[k], scores[k], 1e-9 * scores[k]) << k;
  const std::vector<std::vector<std::uint32_t>> levels = cells_by_sample(unobserved, 4096, boost);
  const detail::Race sampled =
      detail::race_candidates(levels, views, first, factor, list, {.boost = boost});
  EXPECT_EQ(sampled.winner, choose_best(scores));
  const detail::Race stopped = detail::race_candidates(levels, views, first, factor, list,
                                                       {.most_new_targets = 5000, .boost = boost});
  EXPECT_FALSE(stopped.exact);
  EXPECT_EQ(stopped.alive, (std::vector<std::size_t>{1, 2}));
  EXPECT_TRUE(stopped.winner == 1 || stopped.winner == 2);
  // Counting a cell the sample may have missed, the race still ends before the full lists here,
  // with the same winner.
  const detail::Race cautious =
      detail::race_candidates(levels, views, first, factor, list, {.unseen = true, .boost = boost});
  EXPECT_EQ(cautious.winner, choose_best(scores));
  EXPECT_GT(cautious.bits, 0);
}

// The paper's model raced on its per-target v_M (the swept search's lister for it): on the full
// lists, the exact evaluation's argmax by cells and its sums.
TEST(Race, ThePaperModelsRaceOnTheFullListsIsTheExactArgmax) {
  constexpr std::size_t kAll = std::numeric_limits<std::size_t>::max();
  const OccupancyGrid grid = slab_grid();
  const GainMap map(grid, 1);
  const std::vector<Frustum> views{view_from(-0.4), view_from(0.0), view_from(0.3)};
  const std::vector<std::size_t> first{0, 1, 2, 3};
  const std::vector<double> factor{1.0, 1.0, 1.0};
  GainConfig gain;
  gain.method = GainMethod::kProbabilistic;
  gain.alpha = 0.997;
  gain.evaluation = GainEvaluation::kExact;
  gain.num_threads = 1;
  const std::vector<ViewGain> exact = exact_view_gains(map, views, gain);
  const std::vector<double> scores{exact[0].cells, exact[1].cells, exact[2].cells};
  ASSERT_GT(scores[choose_best(scores)], 0.0);
  const detail::Race race =
      detail::race_candidates(unobserved_by_sample(ClassMap(grid), kAll), views, first, factor,
                              [&](std::span<const Frustum> raced, std::span<const std::size_t>,
                                  std::span<const std::uint32_t> cells) {
                                return paper_view_cells(map, raced, gain, cells);
                              });
  EXPECT_TRUE(race.exact);
  EXPECT_EQ(race.winner, choose_best(scores));
  for (std::size_t k = 0; k < scores.size(); ++k)
    EXPECT_NEAR(race.scores[k], scores[k], 1e-9 * scores[k]) << k;
}

}  // namespace
}  // namespace vantage
