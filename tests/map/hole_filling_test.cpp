// MRF/ICM hole filling (§4.4): fills holes in object surfaces, nothing else.

#include "vantage/map/hole_filling.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace vantage {
namespace {

GridSpec cube_spec(int n) {
  GridSpec spec;
  spec.resolution = 0.01;
  spec.dims = Index3::Constant(n);
  return spec;
}

// A box whose front face (x = 2) was seen with a few missing cells (Fig. 6): free space in front
// of it, its other faces and inside unobserved.
struct PartlySeenBox {
  OccupancyGrid grid{cube_spec(12)};
  std::vector<Index3> holes = {{2, 4, 4}, {2, 6, 7}, {2, 8, 5}};

  PartlySeenBox() {
    const GridSpec& spec = grid.spec();
    for (int z = 0; z < 12; ++z) {
      for (int y = 0; y < 12; ++y) {
        for (int x = 0; x < 2; ++x) grid.miss(spec.linear({x, y, z}));               // seen free
        if (y >= 2 && y <= 9 && z >= 2 && z <= 9) grid.hit(spec.linear({2, y, z}));  // the face
      }
    }
    for (const Index3& h : holes) grid.set_log_odds(spec.linear(h), 0.0f);
  }
};

TEST(HoleFilling, FillsTheMissingFaceCellsOfAPartlySeenBox) {
  PartlySeenBox box;
  const CellCounts before = box.grid.counts();
  const HoleFillingResult result = fill_holes(box.grid, HoleFillingConfig{});
  for (const Index3& h : box.holes) {
    EXPECT_EQ(box.grid.state(box.grid.spec().linear(h)), CellState::kOccupied) << h.transpose();
  }
  EXPECT_EQ(result.filled.size(), box.holes.size());  // and nothing else
  EXPECT_EQ(box.grid.counts().occupied, before.occupied + box.holes.size());
  EXPECT_GE(result.sweeps, 2);  // the last sweep changed nothing
}

TEST(HoleFilling, LeavesAnIsolatedUnobservedCellInFreeSpace) {
  OccupancyGrid grid(cube_spec(5));
  for (std::size_t i = 0; i < grid.size(); ++i) grid.miss(i);
  const std::size_t lone = grid.spec().linear({2, 2, 2});
  grid.set_log_odds(lone, 0.0f);
  const HoleFillingResult result = fill_holes(grid, HoleFillingConfig{});
  EXPECT_TRUE(result.filled.empty());
  EXPECT_EQ(grid.state(lone), CellState::kUnobserved);
}

OccupancyGrid random_grid(std::uint64_t seed) {
  OccupancyGrid grid(cube_spec(16));
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> kind(0, 9);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const int k = kind(rng);
    if (k < 4)
      grid.hit(i);
    else if (k < 6)
      grid.miss(i);
  }
  return grid;
}

TEST(HoleFilling, NeverChangesAnOccupiedOrFreeCell) {
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    OccupancyGrid grid = random_grid(seed);
    const OccupancyGrid before = grid;
    const HoleFillingResult result = fill_holes(grid, HoleFillingConfig{});
    EXPECT_FALSE(result.filled.empty());
    for (std::size_t i = 0; i < grid.size(); ++i) {
      if (before.state(i) != CellState::kUnobserved) {
        ASSERT_EQ(grid.log_odds(i), before.log_odds(i)) << "cell " << i;
      } else if (std::binary_search(result.filled.begin(), result.filled.end(), i)) {
        ASSERT_EQ(grid.state(i), CellState::kOccupied);
      } else {
        ASSERT_EQ(grid.state(i), CellState::kUnobserved);
      }
    }
  }
}

TEST(HoleFilling, EnergyNeverIncreasesFromSweepToSweep) {
  for (std::uint64_t seed = 10; seed < 15; ++seed) {
    IcmField field(random_grid(seed), 1.0, 1.0);
    double energy = field.energy();
    int sweeps = 0;
    for (std::size_t changed = 1; changed != 0; ++sweeps) {
      changed = field.sweep();
      const double next = field.energy();
      ASSERT_LE(next, energy) << "seed " << seed << " sweep " << sweeps;
      if (changed != 0) {
        ASSERT_LT(next, energy);
      }
      energy = next;
    }
    EXPECT_GE(sweeps, 2);
  }
}

TEST(HoleFilling, DisabledDoesNothingAndBadConfigIsRejected) {
  PartlySeenBox box;
  HoleFillingConfig config;
  config.enabled = false;
  EXPECT_TRUE(fill_holes(box.grid, config).filled.empty());
  config = {};
  config.beta = -1.0;
  EXPECT_THROW(fill_holes(box.grid, config), std::invalid_argument);
}

}  // namespace
}  // namespace vantage
