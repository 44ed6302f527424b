#pragma once
/// @file
/// How the metrics' oracles (metrics_test.cpp, metrics_scenes_test.cpp) hold the jumping walk
/// (metric_view_gains) to the reference walk (metric_view_gains_reference).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "vantage/gain/evaluators/metric_evaluator.hpp"

namespace vantage::test {

/// The view a decision takes: the first of the highest value.
inline std::size_t best_of(const std::vector<ViewGain>& gains) {
  return static_cast<std::size_t>(
      std::max_element(gains.begin(), gains.end(),
                       [](const ViewGain& a, const ViewGain& b) { return a.gain < b.gain; }) -
      gains.begin());
}

/// The same decision, and per view the same value and cells to the last bit: the jump across a
/// free cube is the one walker's (GridWalk::leave_box), which lands where stepping cell by cell
/// lands, ties between axes included (docs/model.md, "The metrics at speed").
inline void expect_like_reference(const std::vector<ViewGain>& fast,
                                  const std::vector<ViewGain>& reference, const std::string& what) {
  ASSERT_EQ(fast.size(), reference.size()) << what;
  EXPECT_EQ(best_of(fast), best_of(reference)) << what;
  for (std::size_t v = 0; v < fast.size(); ++v) {
    EXPECT_EQ(fast[v].gain, reference[v].gain) << what << ", view " << v;
    EXPECT_EQ(fast[v].cells, reference[v].cells) << what << ", view " << v;
  }
  EXPECT_GT(reference[best_of(reference)].gain, 0.0) << what;
}

}  // namespace vantage::test
