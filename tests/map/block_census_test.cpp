// The census and the packed classes the grid keeps (vantage/map/block_census.hpp,
// cell_classes.hpp) against a count of every block's cells and every cell's class after random
// updates of every kind, on a grid whose sides are not multiples of a block.

#include "vantage/map/block_census.hpp"

#include <gtest/gtest.h>

#include <array>
#include <random>
#include <utility>
#include <vector>

#include "vantage/map/occupancy_grid.hpp"

namespace vantage {
namespace {

/// Every block's cells of each class, counted cell by cell.
std::vector<std::array<int, 3>> counted(const OccupancyGrid& grid) {
  const BlockCensus& census = grid.census();
  std::vector<std::array<int, 3>> counts(census.size(), {0, 0, 0});
  const GridSpec& spec = grid.spec();
  for (std::size_t i = 0; i < grid.size(); ++i) {
    ++counts[census.block_of(spec.unravel(i))][static_cast<std::size_t>(grid.state(i))];
  }
  return counts;
}

void expect_census(const OccupancyGrid& grid) {
  for (std::size_t i = 0; i < grid.size(); ++i) ASSERT_EQ(grid.classes()[i], grid.state(i)) << i;
  const std::vector<std::array<int, 3>> counts = counted(grid);
  const BlockCensus& census = grid.census();
  for (std::size_t b = 0; b < census.size(); ++b) {
    for (const CellState s : {CellState::kUnobserved, CellState::kFree, CellState::kOccupied}) {
      ASSERT_EQ(census.count(b, s), counts[b][static_cast<std::size_t>(s)]) << "block " << b;
    }
    std::uint8_t classes = 0;
    for (std::size_t s = 0; s < 3; ++s) {
      if (counts[b][s] != 0) classes |= class_bit(static_cast<CellState>(s));
    }
    ASSERT_EQ(census.classes(b), classes) << "block " << b;
  }
}

TEST(Divider, DividesEveryThirtyTwoBitNumberExactly) {
  std::mt19937 rng(9);
  std::uniform_int_distribution<std::uint32_t> any;
  for (const std::uint32_t d : {1u, 2u, 3u, 7u, 64u, 65u, 129u, 1000u, 4095u, 65537u, any(rng)}) {
    const Divider by(d);
    for (const std::uint32_t n : {0u, 1u, d - 1, d, d + 1, 0xffffffffu, 0xfffffffeu}) {
      ASSERT_EQ(by(n), n / d) << n << " / " << d;
    }
    for (int k = 0; k < 100000; ++k) {
      const std::uint32_t n = any(rng);
      ASSERT_EQ(by(n), n / d) << n << " / " << d;
    }
  }
}

TEST(BlockCensus, KeepsEveryBlocksCountsThroughRandomUpdates) {
  OccupancyGrid grid(GridSpec::centered({0, 0, 0}, 0.1, {13, 9, 6}));
  EXPECT_EQ(grid.census().dims(), Index3(4, 3, 2));
  expect_census(grid);
  std::mt19937 rng(5);
  std::uniform_int_distribution<std::size_t> cell(0, grid.size() - 1);
  std::uniform_int_distribution<int> kind(0, 3);
  std::uniform_real_distribution<double> p(0.05, 0.95);
  for (int k = 0; k < 4000; ++k) {
    const std::size_t i = cell(rng);
    switch (kind(rng)) {
      case 0:
        grid.hit(i);
        break;
      case 1:
        grid.miss(i);
        break;
      case 2:
        grid.set_probability(i, p(rng));
        break;
      default:
        grid.set_log_odds(i, 0.0f);
        break;
    }
  }
  expect_census(grid);
  const CellCounts c = grid.counts();
  EXPECT_EQ(c.unobserved + c.free + c.occupied, grid.size());
  EXPECT_GT(c.free, 0u);
  EXPECT_GT(c.occupied, 0u);
  grid.reset();
  expect_census(grid);
  EXPECT_EQ(grid.counts().unobserved, grid.size());
}

// The walk block by block (for_block_runs) visits every cell of the slices asked for once, in
// ascending linear index, each run inside the census's block of its cells, on a grid whose sides
// are not multiples of a block.
TEST(BlockCensus, BlockRunsVisitEveryCellOnceInOrderWithinItsBlock) {
  const GridSpec spec = GridSpec::centered({0.0, 0.0, 0.0}, 0.1, {11, 6, 9});
  const BlockCensus census(spec.dims);
  for (const auto& [z0, z1] : {std::pair{0, 9}, std::pair{3, 7}}) {
    std::vector<std::size_t> visited;
    for_block_runs(spec, z0, z1, [&](std::size_t block, std::size_t first, int n) {
      ASSERT_GE(n, 1);
      ASSERT_LE(n, BlockCensus::kBlock);
      for (std::size_t i = first; i < first + static_cast<std::size_t>(n); ++i) {
        ASSERT_EQ(census.block_of(spec.unravel(i)), block) << i;
        visited.push_back(i);
      }
    });
    const std::size_t slice = static_cast<std::size_t>(spec.dims.x() * spec.dims.y());
    std::vector<std::size_t> want(slice * static_cast<std::size_t>(z1 - z0));
    for (std::size_t k = 0; k < want.size(); ++k)
      want[k] = static_cast<std::size_t>(z0) * slice + k;
    EXPECT_EQ(visited, want) << z0;
  }
}

}  // namespace
}  // namespace vantage
