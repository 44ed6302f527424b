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
      EXPECT_FALSE(t.has_objective || t.counts) << t.name;
    } else {
      EXPECT_EQ(t.metric, nullptr) << t.name;
      EXPECT_NE(t.ray, TargetRay::kNone) << t.name;
      EXPECT_FALSE(t.needs_distances) << t.name;
    }
  }
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
      if (t.counts) {
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
