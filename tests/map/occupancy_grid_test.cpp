#include "vantage/map/occupancy_grid.hpp"

#include <gtest/gtest.h>

namespace vantage {
namespace {

OccupancyGrid small_grid() { return OccupancyGrid(GridSpec::centered({0, 0, 0}, 0.1, {4, 4, 4})); }

TEST(OccupancyGrid, StartsUnknown) {
  const OccupancyGrid grid = small_grid();
  EXPECT_DOUBLE_EQ(grid.probability(5), 0.5);
  EXPECT_EQ(grid.counts().unobserved, 64u);
}

TEST(OccupancyGrid, OneMissIsFreeOneHitIsOccupied) {
  OccupancyGrid grid = small_grid();
  grid.miss(0);
  EXPECT_EQ(grid.state(0), CellState::kFree);  // p = 0.4 exactly is free (docs/model.md)
  EXPECT_NEAR(grid.probability(0), 0.4, 1e-6);
  grid.hit(1);
  EXPECT_EQ(grid.state(1), CellState::kOccupied);
  EXPECT_NEAR(grid.probability(1), 0.7, 1e-6);
  // A hit then two misses comes back into the unobserved band.
  grid.miss(1);
  EXPECT_EQ(grid.state(1), CellState::kOccupied);
  grid.miss(1);
  EXPECT_EQ(grid.state(1), CellState::kUnobserved);
}

TEST(OccupancyGrid, ClampsLikeOctoMap) {
  OccupancyGrid grid = small_grid();
  for (int i = 0; i < 50; ++i) grid.hit(2), grid.miss(3);
  EXPECT_NEAR(grid.probability(2), 0.97, 1e-6);
  EXPECT_NEAR(grid.probability(3), 0.12, 1e-6);
}

TEST(OccupancyGrid, RejectsBadParameters) {
  OccupancyParams params;
  params.p_hit = 0.4;
  EXPECT_THROW(OccupancyGrid(GridSpec::centered({0, 0, 0}, 0.1, {2, 2, 2}), params),
               std::invalid_argument);
  params = {};
  params.p_min = 0.0;
  EXPECT_THROW(params.validate(), std::invalid_argument);
}

TEST(Classify, ThresholdsOfModel) {
  EXPECT_EQ(classify(0.4), CellState::kFree);
  EXPECT_EQ(classify(0.41), CellState::kUnobserved);
  EXPECT_EQ(classify(0.59), CellState::kUnobserved);
  EXPECT_EQ(classify(0.6), CellState::kOccupied);
}

}  // namespace
}  // namespace vantage
