#include "vantage/planner/choose.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace vantage {
namespace {

TEST(Choose, BestTiesGoToTheLowerIndex) {
  EXPECT_EQ(choose_best(std::vector<double>{1.0, 3.0, 2.0, 3.0}), 1u);
  EXPECT_THROW(choose_best(std::vector<double>{}), std::invalid_argument);
  EXPECT_THROW(choose_best(std::vector<double>{1.0, std::nan("")}), std::invalid_argument);
}

// issue 27: Yamauchi's nearest candidate; of headings at the same spot (the same travel), the
// one that sees 13,653 cells wins over the one that sees none.
TEST(Choose, TiesOnTheScoreGoToTheHigherTieBreak) {
  const std::vector<double> minus_travel = {-2.0, -1.0, -1.0, -1.0, -3.0};
  const std::vector<double> gains = {50000.0, 0.0, 13653.0, 13653.0, 1e9};
  EXPECT_EQ(choose_best(minus_travel, gains), 2u);  // then the lower index
  EXPECT_EQ(choose_best(minus_travel, std::vector<double>(5, 0.0)), 1u);
  EXPECT_THROW(choose_best(minus_travel, std::vector<double>(4, 0.0)), std::invalid_argument);
  std::vector<double> nan = gains;
  nan[0] = std::nan("");
  EXPECT_THROW(choose_best(minus_travel, nan), std::invalid_argument);
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
