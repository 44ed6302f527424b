#include "vantage/planner/choose.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace vantage {
namespace {

TEST(Choose, BestTiesGoToTheLowerIndex) {
  EXPECT_EQ(choose_best(std::vector<double>{1.0, 3.0, 2.0, 3.0}), 1u);
  EXPECT_THROW(choose_best(std::vector<double>{}), std::invalid_argument);
  EXPECT_THROW(choose_best(std::vector<double>{1.0, std::nan("")}), std::invalid_argument);
}

TEST(Choose, RandomIsSeededAndCoversAllViews) {
  EXPECT_EQ(choose_random(30, 5), choose_random(30, 5));
  std::vector<int> hits(30, 0);
  for (std::uint64_t seed = 0; seed < 3000; ++seed) ++hits[choose_random(30, seed)];
  for (const int h : hits) {
    EXPECT_GT(h, 50);  // about 100 each
    EXPECT_LT(h, 150);
  }
  EXPECT_THROW(choose_random(0, 1), std::invalid_argument);
}

}  // namespace
}  // namespace vantage
