// The exact gain evaluation's own properties: the snapshot it reads against the grid, views that
// share an origin, the façade's dispatch and settings, and its early
// stop against the literal model on synthetic table-top map states after 1, 3 and 6 scans. The
// exact evaluation against hand-computed values: view_gain_test.cpp.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>

#include "bench/synthetic_tabletop.hpp"
#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/ray_model.hpp"
#include "vantage/gain/view_gain.hpp"

namespace vantage {
namespace {

// ---------------------------------------------------------------------------------------------
// The snapshot

TEST(GainMap, HoldsTheGridsProbabilitiesAndClasses) {
  OccupancyGrid grid(GridSpec::centered({0, 0, 0}, 0.05, {23, 17, 11}));
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> op(0, 4);
  for (int sweep = 0; sweep < 4; ++sweep) {
    for (std::size_t i = 0; i < grid.size(); ++i) {
      const int k = op(rng);
      if (k == 0) grid.hit(i);
      if (k == 1 || k == 2) grid.miss(i);
    }
  }
  const GainMap map(grid, 2);
  EXPECT_EQ(map.code_width(), 1);
  EXPECT_LE(map.values().size(), 256u);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    ASSERT_EQ(map.value(i).p, grid.probability(i)) << "cell " << i;
    ASSERT_EQ(map.value(i).state, grid.state(i)) << "cell " << i;
    ASSERT_DOUBLE_EQ(map.value(i).entropy, entropy_bits(grid.probability(i)));
  }
  EXPECT_TRUE(std::is_sorted(map.values().begin(), map.values().end(),
                             [](const auto& a, const auto& b) { return a.p < b.p; }));
}

// The snapshot of the classes alone (for the metrics that read a cell's class only): every cell's
// class as the grid's, on a grid of 4 301 cells (the last packed byte holds one cell), on one
// thread and two; its values ascending, each its class's nominal one.
TEST(GainMap, OfClassesHoldsEveryCellsClass) {
  OccupancyGrid grid(GridSpec::centered({0, 0, 0}, 0.05, {23, 17, 11}));
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> op(0, 3);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const int k = op(rng);
    if (k == 0) grid.hit(i);
    if (k == 1) grid.miss(i);
  }
  for (const int threads : {1, 2}) {
    const GainMap map = GainMap::of_classes(grid, threads);
    ASSERT_EQ(map.size(), grid.size());
    EXPECT_EQ(map.code_width(), 1);
    ASSERT_EQ(map.values().size(), 3u);
    for (std::size_t i = 0; i < grid.size(); ++i) {
      ASSERT_EQ(map.value(i).state, grid.state(i)) << "cell " << i;
      const double nominal = grid.state(i) == CellState::kUnobserved ? 0.5
                             : grid.state(i) == CellState::kFree     ? 0.0
                                                                     : 1.0;
      ASSERT_EQ(map.value(i).p, nominal) << "cell " << i;
      ASSERT_EQ(map.value(i).entropy, entropy_bits(nominal)) << "cell " << i;
    }
    EXPECT_TRUE(std::is_sorted(map.values().begin(), map.values().end(),
                               [](const auto& a, const auto& b) { return a.p < b.p; }));
  }
}

TEST(GainMap, WidensItsCodesForManyDistinctValues) {
  OccupancyGrid grid(GridSpec::centered({0, 0, 0}, 0.05, {40, 40, 4}));
  for (std::size_t i = 0; i < grid.size(); ++i) {
    grid.set_log_odds(i, -2.0f + 4.0f * static_cast<float>(i) / static_cast<float>(grid.size()));
  }
  const GainMap map(grid, 1);
  std::vector<float> distinct(grid.log_odds().begin(), grid.log_odds().end());
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  EXPECT_GT(distinct.size(), 256u);
  EXPECT_EQ(map.code_width(), 2);
  EXPECT_EQ(map.values().size(), distinct.size());
  for (std::size_t i = 0; i < grid.size(); ++i) ASSERT_EQ(map.value(i).p, grid.probability(i));
}

// ---------------------------------------------------------------------------------------------
// Small grids

// A grid of random cells and four views around it, one of them from inside the grid.
struct RandomWorld {
  OccupancyGrid grid{GridSpec::centered({0, 0, 0.25}, 0.02, {40, 40, 25})};
  std::vector<Frustum> views;

  RandomWorld() {
    std::mt19937_64 rng(11);
    std::uniform_int_distribution<int> kind(0, 9);
    for (std::size_t i = 0; i < grid.size(); ++i) {
      const int k = kind(rng);
      if (k < 4) grid.miss(i);
      if (k == 9) grid.hit(i);
    }
    for (int k = 0; k < 3; ++k) {
      const double a = k * 2.0;
      views.emplace_back(look_at({1.2 * std::cos(a), 1.2 * std::sin(a), 0.6}, {0, 0, 0.2}),
                         SensorFov{deg2rad(60), deg2rad(45), 0.3, 3.0});
    }
    views.emplace_back(look_at({0.05, 0.02, 0.3}, {0.4, 0.1, 0.2}), SensorFov{});
  }
};

TEST(ExactGain, ViewsFromOneOriginShareRaysBitForBit) {
  // The exact mode evaluates a cell once for all views from one origin; each view's sums stay
  // bit for bit those of the view evaluated alone.
  const OccupancyGrid grid =
      synthetic::map_after(synthetic::table_top(0), synthetic::grid_spec(), 1, 160, 120);
  const std::vector<Frustum> ring = synthetic::ring_views();
  const std::vector<Frustum> views(ring.begin() + 3, ring.begin() + 9);  // two positions
  const auto groups = views_by_origin(views);
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0], (std::vector<std::size_t>{0, 1, 2}));
  for (const GainMethod method : {GainMethod::kProbabilistic, GainMethod::kGreedy}) {
    GainConfig config;
    config.method = method;
    const auto together = exact_view_gains(grid, views, config);
    for (std::size_t v = 0; v < views.size(); ++v) {
      const ViewGain alone = exact_view_gains(grid, std::span(&views[v], 1), config).front();
      EXPECT_GT(alone.targets, 0u);
      EXPECT_EQ(alone.gain, together[v].gain) << to_string(method) << ", view " << v;
      EXPECT_EQ(alone.cells, together[v].cells) << to_string(method) << ", view " << v;
      EXPECT_EQ(alone.targets, together[v].targets) << to_string(method) << ", view " << v;
    }
  }
}

TEST(ExactGain, ViewsThatSeeNoGridGainNothing) {
  const OccupancyGrid grid(GridSpec::centered({0, 0, 0}, 0.05, {20, 20, 10}));
  std::vector<Frustum> views = {Frustum(look_at({2, 0, 0}, {4, 0, 0}), SensorFov{}),
                                Frustum(look_at({0, 0, 30}, {0, 0, 0}), SensorFov{})};
  for (const ViewGain& g : exact_view_gains(grid, views, GainConfig{})) {
    EXPECT_EQ(g.targets, 0u);
    EXPECT_EQ(g.gain, 0.0);
    EXPECT_EQ(g.cells, 0.0);
  }
}

TEST(EvaluateViews, AutoAndExactAreTheExactEvaluation) {
  const RandomWorld world;
  GainConfig config;
  const auto automatic = evaluate_views(world.grid, world.views, config);
  config.evaluation = GainEvaluation::kExact;
  const auto exact = evaluate_views(world.grid, world.views, config);
  const auto reference = exact_view_gains(world.grid, world.views, config);
  for (std::size_t v = 0; v < world.views.size(); ++v) {
    EXPECT_EQ(automatic[v].gain, reference[v].gain);
    EXPECT_EQ(exact[v].gain, reference[v].gain);
  }
  EXPECT_EQ(GainConfig{}.evaluation, GainEvaluation::kAuto);  // the default, see BENCHMARK.md
}

TEST(GainConfig, RejectsBadEpsilonAndRaySpacing) {
  GainConfig config;
  config.epsilon = -1e-9;
  EXPECT_THROW(config.validate(), std::invalid_argument);
  config.epsilon = 0.5;
  EXPECT_THROW(config.validate(), std::invalid_argument);
  config.epsilon = 0.0;
  EXPECT_NO_THROW(config.validate());
  config.ray_spacing = 0.0;
  EXPECT_THROW(config.validate(), std::invalid_argument);
  config.ray_spacing = 1.5;
  EXPECT_THROW(config.validate(), std::invalid_argument);
  EXPECT_EQ(parse_gain_evaluation("exact"), GainEvaluation::kExact);
  EXPECT_EQ(parse_gain_evaluation("auto"), GainEvaluation::kAuto);
  EXPECT_THROW(parse_gain_evaluation("quick"), std::invalid_argument);
  // The fast evaluation was removed: the exact one costs as little (BENCHMARK.md, "One planner").
  EXPECT_THROW(parse_gain_evaluation("fast"), std::invalid_argument);
  EXPECT_EQ(to_string(GainEvaluation::kAuto), "auto");
}

// ---------------------------------------------------------------------------------------------
// The early stop

TEST(ExactGain, EarlyStopChangesNothingMeasurable) {
  // The denser synthetic table top after 6 scans from the ring: the most scanned state, where
  // most rays are hidden early. The built-in scenes of vantage::sim: gain_scenes_test.cpp.
  const std::vector<Frustum> views = synthetic::ring_views();
  const OccupancyGrid grid =
      synthetic::map_after(synthetic::table_top(1), synthetic::grid_spec(), 6, 320, 240);
  GainConfig literal;
  literal.epsilon = 0.0;
  const auto a = exact_view_gains(grid, views, literal);
  const auto b = exact_view_gains(grid, views, GainConfig{});
  for (std::size_t v = 0; v < views.size(); ++v) {
    EXPECT_NEAR(b[v].gain, a[v].gain, 1e-4 * a[v].gain) << "view " << v;
    EXPECT_EQ(b[v].targets, a[v].targets);
  }
}

}  // namespace
}  // namespace vantage
