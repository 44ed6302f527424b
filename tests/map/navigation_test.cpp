// Navigation: A* through a small maze gives the known shortest path, an unreachable goal gives
// the nearest reachable place, inflation and the height band work, and A* agrees with Dijkstra.

#include "vantage/map/navigation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace vantage {
namespace {

// 1 m cells; '#' obstacle. Row 0 of the picture is y = 4. A footprint of 0.5 m inflates nothing
// beyond the obstacle cells themselves (centres 1 m apart).
//   y=4  S . . . .
//   y=3  # # # # .
//   y=2  . . . . .
//   y=1  . # # # #
//   y=0  . . . . G
NavigationGrid maze() {
  const std::vector<std::string> rows = {"S....", "####.", ".....", ".####", "....G"};
  std::vector<std::uint8_t> obstacles(25, 0);
  for (int r = 0; r < 5; ++r) {
    for (int x = 0; x < 5; ++x) obstacles[x + 5 * (4 - r)] = rows[r][x] == '#';
  }
  return {Eigen::Vector2d::Zero(), 1.0, {5, 5}, obstacles, 0.5};
}

Eigen::Vector2d centre(int x, int y) { return {x + 0.5, y + 0.5}; }

TEST(Navigation, AStarFindsTheKnownShortestPathThroughAMaze) {
  const NavigationGrid nav = maze();
  const NavigationPath path = find_path(nav, centre(0, 4), centre(4, 0));
  ASSERT_TRUE(path.reached);
  // No corner may be cut, so the only shortest path snakes through all three corridors:
  // 4 + 2 + 4 + 2 + 4 = 16 orthogonal moves.
  EXPECT_DOUBLE_EQ(path.length, 16.0);
  const std::vector<Index2> expected = {{0, 4}, {1, 4}, {2, 4}, {3, 4}, {4, 4}, {4, 3},
                                        {4, 2}, {3, 2}, {2, 2}, {1, 2}, {0, 2}, {0, 1},
                                        {0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}};
  ASSERT_EQ(path.points.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    EXPECT_TRUE(path.points[k].isApprox(centre(expected[k].x(), expected[k].y())))
        << "step " << k << ": " << path.points[k].transpose();
  }
  EXPECT_TRUE(path.end.isApprox(centre(4, 0)));

  // Dijkstra from the start agrees.
  const TravelMap travel(nav, centre(0, 4));
  EXPECT_DOUBLE_EQ(travel.distance({4, 0}), 16.0);
  EXPECT_DOUBLE_EQ(travel.distance({4, 3}), 5.0);
  EXPECT_FALSE(travel.reachable({1, 1}));  // an obstacle
}

TEST(Navigation, UnreachableGoalGivesTheNearestReachablePlace) {
  const NavigationGrid nav = maze();
  // The goal lies in the wall at (2, 3): its neighbours (2, 2) and (2, 4) are equally near, and
  // the tie goes to the lower index, (2, 2), 8 m away.
  const NavigationPath wall = find_path(nav, centre(0, 4), centre(2, 3));
  EXPECT_FALSE(wall.reached);
  EXPECT_TRUE(wall.end.isApprox(centre(2, 2))) << wall.end.transpose();
  EXPECT_DOUBLE_EQ(wall.length, 8.0);
  EXPECT_TRUE(wall.points.back().isApprox(centre(2, 2)));

  // A goal outside the grid: the nearest cell the robot reaches.
  const NavigationPath outside = find_path(nav, centre(0, 4), {7.0, -3.0});
  EXPECT_FALSE(outside.reached);
  EXPECT_TRUE(outside.end.isApprox(centre(4, 0))) << outside.end.transpose();

  // A closed room: a goal inside it ends at the reachable cell nearest to it.
  std::vector<std::uint8_t> obstacles(49, 0);
  for (int k = 2; k <= 6; ++k) {  // the room's walls: x = 2 and y = 2 lines from (2, 2) to (6, 6)
    obstacles[2 + 7 * k] = 1;
    obstacles[k + 7 * 2] = 1;
  }
  const NavigationGrid room(Eigen::Vector2d::Zero(), 1.0, {7, 7}, obstacles, 0.5);
  const NavigationPath closed = find_path(room, centre(0, 0), centre(5, 5));
  EXPECT_FALSE(closed.reached);
  // (1, 5) and (5, 1) lie 4 m from the goal's centre, nearer than any other reachable cell; the
  // tie goes to the lower index, (5, 1).
  EXPECT_TRUE(closed.end.isApprox(centre(5, 1))) << closed.end.transpose();
  EXPECT_NEAR(closed.length, 4.0 + std::sqrt(2.0), 1e-12);  // one diagonal step
}

TEST(Navigation, AFrontierStopIsTheRegionsOwnReachableCellNearestItsCentroid) {
  const NavigationGrid nav = maze();
  const TravelMap travel(nav, centre(0, 4));
  // A region along the wall at y = 3 and the corridor below it: its centroid (2, 3) lies in the
  // wall. The fallback drives to (2, 2) whatever the region; the projection picks the region's
  // own reachable cell nearest the centroid, (3, 2) before (1, 2) here because it comes first.
  const std::vector<Eigen::Vector2d> region = {centre(3, 3), centre(3, 2), centre(1, 3),
                                               centre(1, 2), centre(0, 0)};
  const std::optional<Index2> stop = travel.nearest_reachable_among(region, centre(2, 3));
  ASSERT_TRUE(stop.has_value());
  EXPECT_EQ(*stop, Index2(3, 2));
  // Cells in walls or outside the grid are never chosen; none reachable gives nothing.
  const std::vector<Eigen::Vector2d> walled = {centre(1, 3), centre(2, 3), {9.0, 9.0}};
  EXPECT_FALSE(travel.nearest_reachable_among(walled, centre(2, 3)).has_value());
}

TEST(Navigation, InflationKeepsTheBaseClearOfObstacles) {
  // One obstacle in the middle of a 21 x 21 grid of 0.1 m cells; footprint 0.668 m.
  std::vector<std::uint8_t> obstacles(21 * 21, 0);
  obstacles[10 + 21 * 10] = 1;
  const NavigationGrid nav(Eigen::Vector2d::Zero(), 0.1, {21, 21}, obstacles, 0.668);
  for (std::size_t i = 0; i < nav.size(); ++i) {
    const double d = (nav.center(nav.unravel(i)) - nav.center({10, 10})).norm();
    EXPECT_EQ(nav.blocked(i), d <= 0.334) << nav.unravel(i).transpose();
  }
  // A robot that starts inside the inflated disc (a new obstacle seen next to it) can drive out.
  const NavigationPath out = find_path(nav, nav.center({12, 10}), nav.center({20, 10}));
  EXPECT_TRUE(out.reached);
}

TEST(Navigation, MapObstaclesComeFromTheHeightBand) {
  // 0.1 m cells, 10 x 10 x 20 (2 m high). Occupied: a floor cell (z = 0.05, below the band),
  // a cell at 1.0 m (in it) and one at 1.85 m (above the robot).
  OccupancyGrid grid(GridSpec{Eigen::Vector3d::Zero(), 0.1, {10, 10, 20}});
  const GridSpec& spec = grid.spec();
  grid.set_probability(spec.linear({1, 1, 0}), 0.9);
  grid.set_probability(spec.linear({5, 5, 9}), 0.9);
  grid.set_probability(spec.linear({8, 2, 18}), 0.9);
  NavigationConfig config;
  config.footprint = 0.1;  // no inflation beyond the cell
  NavigationGrid nav = NavigationGrid::from_map(grid, config);
  EXPECT_FALSE(nav.obstacle(nav.linear({1, 1})));
  EXPECT_TRUE(nav.obstacle(nav.linear({5, 5})));
  EXPECT_FALSE(nav.obstacle(nav.linear({8, 2})));
  EXPECT_FALSE(nav.obstacle(nav.linear({0, 0})));  // unknown counts as free by default
  config.unknown_blocks = true;
  nav = NavigationGrid::from_map(grid, config);
  EXPECT_TRUE(nav.obstacle(nav.linear({0, 0})));

  std::vector<std::uint8_t> occupied(spec.num_cells(), 0);
  occupied[spec.linear({3, 4, 5})] = 1;
  nav = NavigationGrid::from_occupancy(spec, occupied, NavigationConfig{.footprint = 0.1});
  EXPECT_TRUE(nav.obstacle(nav.linear({3, 4})));
  EXPECT_FALSE(nav.obstacle(nav.linear({4, 4})));
  EXPECT_THROW(NavigationGrid::from_occupancy(spec, std::vector<std::uint8_t>(3, 0), {}),
               std::invalid_argument);
  EXPECT_THROW(NavigationGrid::from_map(grid, NavigationConfig{.footprint = -1.0}),
               std::invalid_argument);
}

TEST(Navigation, CombinedGridsHoldTheObstaclesOfBoth) {
  // The maze, and a map that also saw an obstacle at (2, 2): the corridor y = 2 is cut, so the
  // goal at (4, 0) cannot be reached any more.
  const NavigationGrid truth = maze();
  std::vector<std::uint8_t> seen(25, 0);
  seen[2 + 5 * 2] = 1;
  const NavigationGrid map(Eigen::Vector2d::Zero(), 1.0, {5, 5}, seen, 0.5);
  const NavigationGrid both = NavigationGrid::combine(truth, map);
  for (std::size_t i = 0; i < both.size(); ++i) {
    EXPECT_EQ(both.obstacle(i), truth.obstacle(i) || map.obstacle(i)) << i;
  }
  const NavigationPath path = find_path(both, centre(0, 4), centre(4, 0));
  EXPECT_FALSE(path.reached);
  EXPECT_TRUE(path.end.isApprox(centre(4, 2))) << path.end.transpose();  // 2 m from the goal
  const NavigationGrid other(Eigen::Vector2d::Zero(), 0.5, {5, 5}, seen, 0.5);
  EXPECT_THROW(NavigationGrid::combine(truth, other), std::invalid_argument);
}

TEST(Navigation, AStarAgreesWithDijkstraOnRandomGrids) {
  std::mt19937 rng(3);
  std::bernoulli_distribution wall(0.3);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<std::uint8_t> obstacles(15 * 12);
    for (auto& o : obstacles) o = wall(rng);
    obstacles[0] = 0;
    const NavigationGrid nav(Eigen::Vector2d(-1.0, 2.0), 0.5, {15, 12}, obstacles, 0.2);
    const Eigen::Vector2d start = nav.center({0, 0});
    const TravelMap travel(nav, start);
    for (std::size_t i = 0; i < nav.size(); i += 7) {
      const Index2 goal = nav.unravel(i);
      const NavigationPath path = find_path(nav, start, nav.center(goal));
      EXPECT_EQ(path.reached, travel.reachable(goal)) << goal.transpose();
      if (!path.reached) continue;
      EXPECT_NEAR(path.length, travel.distance(goal), 1e-9) << goal.transpose();
      double along = 0.0;  // the path's own length, step by step
      for (std::size_t k = 1; k < path.points.size(); ++k) {
        const double step = (path.points[k] - path.points[k - 1]).norm();
        EXPECT_TRUE(std::abs(step - 0.5) < 1e-9 || std::abs(step - 0.5 * std::sqrt(2.0)) < 1e-9);
        along += step;
      }
      EXPECT_NEAR(along, path.length, 1e-9);
    }
  }
}

}  // namespace
}  // namespace vantage
