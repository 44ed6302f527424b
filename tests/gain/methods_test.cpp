// The gain methods' registry (methods.hpp): every method has one row, the rows agree with the
// evaluations they steer, and names parse back.

#include "vantage/gain/methods.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <stdexcept>
#include <string>

#include "row_grid.hpp"
#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/evaluators/metric_evaluator.hpp"
#include "vantage/gain/snapshot.hpp"
#include "vantage/gain/view_gain.hpp"

namespace vantage {
namespace {

TEST(Methods, EveryMethodHasOneRowAndItsNameParsesBack) {
  std::set<std::string_view> names;
  for (const MethodTraits& t : gain_methods()) {
    EXPECT_TRUE(names.insert(t.name).second) << t.name;
    EXPECT_EQ(&method_traits(t.method), &t) << t.name;
    EXPECT_EQ(parse_gain_method(t.name), t.method);
    EXPECT_EQ(find_gain_method(t.name), t.method);
    EXPECT_EQ(to_string(t.method), t.name);
  }
  EXPECT_EQ(names.size(), 11u);
  EXPECT_FALSE(find_gain_method("counting").has_value());
  try {
    parse_gain_method("counting");
    FAIL() << "parsed an unknown method";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'counting' (expected probabilistic, survival, greedy"),
              std::string::npos)
        << e.what();
  }
}

TEST(Methods, AMetricHasAnEvaluationAndATargetModelARay) {
  for (const MethodTraits& t : gain_methods()) {
    if (t.kind == MethodKind::kMetric) {
      EXPECT_NE(t.metric, nullptr) << t.name;
      EXPECT_EQ(t.ray, TargetRay::kNone) << t.name;
      EXPECT_FALSE(t.has_objective()) << t.name;
      EXPECT_EQ(t.by_bits, GainQuantity::kMetric) << t.name;
    } else {
      EXPECT_EQ(t.metric, nullptr) << t.name;
      EXPECT_NE(t.ray, TargetRay::kNone) << t.name;
      EXPECT_FALSE(t.needs_distances) << t.name;
      EXPECT_NE(t.by_cells, GainQuantity::kMetric) << t.name;
    }
  }
}

// "Which quantity" has one answer, the row's, read with the objective.
TEST(Methods, TheRowSaysWhichQuantityAMethodComputes) {
  using Q = GainQuantity;
  const auto quantity = [](GainMethod m, GainObjective o) { return method_traits(m).quantity(o); };
  EXPECT_EQ(quantity(GainMethod::kProbabilistic, GainObjective::kBits), Q::kPaperBits);
  EXPECT_EQ(quantity(GainMethod::kProbabilistic, GainObjective::kCells), Q::kPaperCells);
  EXPECT_EQ(quantity(GainMethod::kSurvival, GainObjective::kBits), Q::kSurvivalBits);
  EXPECT_EQ(quantity(GainMethod::kSurvival, GainObjective::kCells), Q::kSurvivalCells);
  for (const GainObjective o : {GainObjective::kBits, GainObjective::kCells}) {
    EXPECT_EQ(quantity(GainMethod::kGreedy, o), Q::kCount);
    EXPECT_EQ(quantity(GainMethod::kSurface, o), Q::kMetric);
  }
  EXPECT_TRUE(method_traits(GainMethod::kSurvival).has_objective());
  EXPECT_FALSE(method_traits(GainMethod::kGreedy).has_objective());
  // A quantity's value is the field it names; greedy's count is both.
  const ViewGain g{2.0, 3.0, 4};
  EXPECT_EQ(g.value(Q::kPaperBits), 2.0);
  EXPECT_EQ(g.value(Q::kMetric), 2.0);
  EXPECT_EQ(g.value(Q::kSurvivalCells), 3.0);
  EXPECT_EQ(ViewGain::of(Q::kCount, 5.0).gain, 5.0);
  EXPECT_EQ(ViewGain::of(Q::kCount, 5.0).cells, 5.0);
  EXPECT_EQ(ViewGain::of(Q::kSurvivalCells, 5.0).gain, 0.0);
  EXPECT_EQ(ViewGain::of(Q::kSurvivalBits, 5.0).cells, 0.0);
  EXPECT_TRUE(counts_classes(Q::kCount) && counts_classes(Q::kSurvivalCells));
  EXPECT_FALSE(counts_classes(Q::kPaperCells) || counts_classes(Q::kSurvivalBits));
}

// The traits say what the evaluations do: a counting method's bits are its cells and whole
// numbers; a target model gives its exact values under kAuto.
TEST(Methods, TheTraitsDescribeWhatTheEvaluationsDo) {
  const OccupancyGrid grid = test::row_grid();
  const std::vector<Frustum> views = {test::looking_along_x({-0.5, 0.0, 0.0}),
                                      test::looking_along_x({0.25, 0.0, 0.0})};
  for (const MethodTraits& t : gain_methods()) {
    if (t.kind != MethodKind::kTargetModel) continue;
    GainConfig config;
    config.method = t.method;
    config.alpha = 0.99;
    config.num_threads = 1;
    config.evaluation = GainEvaluation::kExact;
    const std::vector<ViewGain> exact = evaluate_views(grid, views, config);
    config.evaluation = GainEvaluation::kAuto;
    const std::vector<ViewGain> automatic = evaluate_views(grid, views, config);
    double total = 0.0;
    for (std::size_t v = 0; v < views.size(); ++v) {
      total += exact[v].cells;
      if (t.by_cells == GainQuantity::kCount) {
        EXPECT_EQ(exact[v].gain, exact[v].cells) << t.name;
        EXPECT_EQ(exact[v].cells, std::round(exact[v].cells)) << t.name;
      }
      EXPECT_EQ(automatic[v].gain, exact[v].gain) << t.name << " view " << v;
    }
    EXPECT_GT(total, 0.0) << t.name;
  }
}

}  // namespace
}  // namespace vantage
