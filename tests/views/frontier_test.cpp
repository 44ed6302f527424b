// Frontier extraction on hand-built grids: the regions and centroids worked out by hand, the
// cell test against a brute-force oracle, and the region-size limit.

#include "vantage/views/frontier.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace vantage {
namespace {

// A 10 x 10 x 3 grid of 1 m cells, all unknown except:
//   a free room x in [0, 4] (all y, all z) whose frontier is the plane x = 4 (its x = 5
//   neighbours are unknown), cut at y = 5 by an occupied cell in every layer;
//   a free pocket x in [7, 9], y in [0, 2], whose frontier is its x = 7 column and y = 2 row.
OccupancyGrid hand_built() {
  OccupancyGrid grid(GridSpec{Eigen::Vector3d::Zero(), 1.0, {10, 10, 3}});
  const GridSpec& spec = grid.spec();
  for (int z = 0; z < 3; ++z) {
    for (int y = 0; y < 10; ++y) {
      for (int x = 0; x < 10; ++x) {
        const std::size_t i = spec.linear({x, y, z});
        if (x == 4 && y == 5) {
          grid.set_probability(i, 0.9);
        } else if (x <= 4 || (x >= 7 && y <= 2)) {
          grid.set_probability(i, 0.2);
        }
      }
    }
  }
  return grid;
}

std::vector<Index3> cells_of(const GridSpec& spec, const FrontierRegion& region) {
  std::vector<Index3> cells;
  for (const std::uint32_t i : region.cells) cells.push_back(spec.unravel(i));
  return cells;
}

TEST(Frontier, HandBuiltGridGivesTheExpectedRegionsAndCentroids) {
  const OccupancyGrid grid = hand_built();
  FrontierConfig config;
  config.min_z = 1.5;  // the middle layer only: its centres lie at z = 1.5
  config.max_z = 1.5;
  config.min_cells = 1;
  config.max_radius = 0.0;  // plain connected components
  const std::vector<FrontierRegion> regions = frontier_regions(grid, config);
  ASSERT_EQ(regions.size(), 3u);

  // Ordered by seed: the room's south part (x = 4, y = 0..4), the pocket (seeded at (7, 0)),
  // the room's north part (x = 4, y = 6..9).
  EXPECT_EQ(regions[0].cells.size(), 5u);
  EXPECT_TRUE(regions[0].centroid.isApprox(Eigen::Vector3d(4.5, 2.5, 1.5), 1e-12))
      << regions[0].centroid.transpose();
  for (const Index3& c : cells_of(grid.spec(), regions[0])) {
    EXPECT_EQ(c.x(), 4);
    EXPECT_LE(c.y(), 4);
  }
  // The pocket: (7, 0), (7, 1), (7, 2), (8, 2), (9, 2).
  EXPECT_EQ(regions[1].cells.size(), 5u);
  EXPECT_TRUE(regions[1].centroid.isApprox(Eigen::Vector3d(8.1, 1.9, 1.5), 1e-12))
      << regions[1].centroid.transpose();
  EXPECT_EQ(regions[2].cells.size(), 4u);
  EXPECT_TRUE(regions[2].centroid.isApprox(Eigen::Vector3d(4.5, 8.0, 1.5), 1e-12))
      << regions[2].centroid.transpose();

  // min_cells drops the 4-cell region.
  config.min_cells = 5;
  EXPECT_EQ(frontier_regions(grid, config).size(), 2u);

  // All three layers: the same regions, three times the cells, centroids at mid height.
  config = FrontierConfig{};
  config.min_cells = 1;
  config.max_radius = 0.0;
  const std::vector<FrontierRegion> all = frontier_regions(grid, config);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].cells.size(), 15u);
  EXPECT_TRUE(all[1].centroid.isApprox(Eigen::Vector3d(8.1, 1.9, 1.5), 1e-12));
}

TEST(Frontier, CellsMatchABruteForceOracle) {
  OccupancyGrid grid(GridSpec{Eigen::Vector3d(-1, 2, 0.5), 0.1, {13, 11, 7}});
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> state(0, 2);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const int s = state(rng);
    if (s == 1) grid.set_probability(i, 0.2);
    if (s == 2) grid.set_probability(i, 0.8);
  }
  FrontierConfig config;
  config.min_z = 0.7;
  config.max_z = 1.0;
  const GridSpec& spec = grid.spec();
  std::vector<std::uint32_t> expected;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const Index3 c = spec.unravel(i);
    const double z = spec.center(c).z();
    if (grid.state(i) != CellState::kFree || z < 0.7 || z > 1.0) continue;
    bool next_to_unknown = false;
    for (const Index3& d : {Index3(1, 0, 0), Index3(-1, 0, 0), Index3(0, 1, 0), Index3(0, -1, 0),
                            Index3(0, 0, 1), Index3(0, 0, -1)}) {
      next_to_unknown |= spec.contains(Index3(c + d)) && grid.is_unobserved(spec.linear(c + d));
    }
    if (next_to_unknown) expected.push_back(static_cast<std::uint32_t>(i));
  }
  ASSERT_FALSE(expected.empty());
  EXPECT_EQ(frontier_cells(grid, config), expected);
  for (const std::uint32_t i : expected) EXPECT_TRUE(is_frontier_cell(grid, i, config));

  // Regions partition the frontier cells when none is dropped, each within reach of its seed.
  config.min_cells = 1;
  config.max_radius = 0.25;
  std::vector<std::uint32_t> covered;
  for (const FrontierRegion& r : frontier_regions(grid, config)) {
    const Eigen::Vector3d seed = spec.center(spec.unravel(r.cells.front()));
    for (const std::uint32_t i : r.cells) {
      EXPECT_LE((spec.center(spec.unravel(i)) - seed).norm(), 0.25 + 1e-12);
      EXPECT_GE(i, r.cells.front());  // the seed is the region's lowest cell
      covered.push_back(i);
    }
  }
  std::sort(covered.begin(), covered.end());
  EXPECT_EQ(covered, expected);
}

TEST(Frontier, LongFrontierSplitsIntoPiecesOfBoundedRadius) {
  const OccupancyGrid grid = hand_built();
  FrontierConfig config;
  config.min_z = 1.5;
  config.max_z = 1.5;
  config.min_cells = 1;
  config.max_radius = 2.0;
  // The room's south part (x = 4, y = 0..4) splits into y = 0..2 and y = 3..4.
  const std::vector<FrontierRegion> regions = frontier_regions(grid, config);
  ASSERT_GE(regions.size(), 4u);
  EXPECT_EQ(regions[0].cells.size(), 3u);
  EXPECT_TRUE(regions[0].centroid.isApprox(Eigen::Vector3d(4.5, 1.5, 1.5), 1e-12));
}

TEST(Frontier, RejectsBadSettings) {
  const OccupancyGrid grid = hand_built();
  FrontierConfig config;
  config.min_z = 2.0;
  config.max_z = 1.0;
  EXPECT_THROW(frontier_regions(grid, config), std::invalid_argument);
  config = FrontierConfig{};
  config.min_cells = 0;
  EXPECT_THROW(frontier_regions(grid, config), std::invalid_argument);
  config = FrontierConfig{};
  config.max_radius = -1.0;
  EXPECT_THROW(frontier_cells(grid, config), std::invalid_argument);
}

}  // namespace
}  // namespace vantage
