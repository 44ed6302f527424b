// The surface model's online fit (vantage/gain/models/surface_rates.hpp): rates counted by hand on
// the row of row_grid.hpp.

#include "vantage/gain/models/surface_rates.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "row_grid.hpp"

namespace vantage {
namespace {

TEST(SurfaceRateFit, ARateIsTheShareOfItsClassTurnedOccupiedAmongThoseTurnedKnown) {
  // Row: 5-7 unobserved at 3, 2, 1 cells from the occupied cell 8 (classes 2, 1, 0); 9-11
  // unobserved at 1, 2, 3 (classes 0, 1, 2). The "scan" turns 7 occupied, 6 and 9 free, and
  // leaves 5, 10 and 11 unobserved.
  OccupancyGrid grid = test::row_grid();
  SurfaceRateFit fit(/*recency=*/0.5, /*prior_cells=*/0.0);
  EXPECT_EQ(fit.rates(), kSurfacePrior);
  fit.before(grid, 1);
  grid.set_probability(7, grid.params().p_max);
  grid.set_probability(6, grid.params().p_min);
  grid.set_probability(9, grid.params().p_min);
  fit.after(grid);
  // Class 0: cells 7 (occupied) and 9 (free): 1 of 2. Class 1: cell 6 (free): 0 of 1. Class 2:
  // none known, and classes 3 and 4 none at all: the prior stays.
  EXPECT_DOUBLE_EQ(fit.rates()[0], 0.5);
  EXPECT_DOUBLE_EQ(fit.rates()[1], 0.0);
  EXPECT_DOUBLE_EQ(fit.rates()[2], kSurfacePrior[2]);
  EXPECT_DOUBLE_EQ(fit.rates()[4], kSurfacePrior[4]);
  EXPECT_DOUBLE_EQ(fit.known()[0], 2.0);

  // A second scan turns cell 10 occupied: 2 cells from cell 8, class 1 (cells 5 and 11 stay
  // unobserved). The older outcome weighs half: class 1 is (0.5 * 0 + 1) / (0.5 * 1 + 1).
  fit.before(grid, 1);
  grid.set_probability(10, grid.params().p_max);
  fit.after(grid);
  EXPECT_DOUBLE_EQ(fit.rates()[1], 1.0 / 1.5);
  EXPECT_DOUBLE_EQ(fit.rates()[0], 0.5);  // 0.5 * 1 / (0.5 * 2)
}

TEST(SurfaceRateFit, APriorOfSomeCellsPullsAFewOutcomesTowardsIt) {
  OccupancyGrid grid = test::row_grid();
  SurfaceRateFit fit(0.5, 2.0);
  fit.before(grid, 1);
  grid.set_probability(7, grid.params().p_max);
  fit.after(grid);
  EXPECT_DOUBLE_EQ(fit.rates()[0], (1.0 + 2.0 * kSurfacePrior[0]) / 3.0);
}

TEST(SurfaceRateFit, BadSettingsAndAnAfterWithoutABeforeAreRefused) {
  EXPECT_THROW(SurfaceRateFit(0.0), std::invalid_argument);
  EXPECT_THROW(SurfaceRateFit(0.5, -1.0), std::invalid_argument);
  SurfaceRateFit fit;
  EXPECT_THROW(fit.after(test::row_grid()), std::logic_error);
}

}  // namespace
}  // namespace vantage
