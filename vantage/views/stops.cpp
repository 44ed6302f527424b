// The stops set (candidate_set.hpp): where a ground robot exploring a building drives next (§5.2).
// Each frontier region's centroid the robot has not visited is a stop, with its drive planned on
// the map: to the centroid when it is reachable, else to the region's reachable cell nearest it
// (project_stops), else to the map's reachable place nearest it (the paper's fallback).

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "vantage/views/candidate_set.hpp"

namespace vantage {
namespace {

/// The drive to a region's centroid on `travel`'s map.
Drive drive_to(const FrontierRegion& region, const GridSpec& spec, const TravelMap& travel,
               bool project) {
  const NavigationGrid& nav = travel.grid();
  Drive drive;
  drive.goal = region.centroid.head<2>();
  drive.arrival = drive.goal;
  std::optional<Index2> cell = nav.cell_of(drive.goal);
  drive.reachable = cell && travel.reachable(*cell);
  if (!drive.reachable && project) {
    std::vector<Eigen::Vector2d> places;
    for (const std::uint32_t i : region.cells)
      places.push_back(spec.center(spec.unravel(i)).head<2>());
    if (const std::optional<Index2> projected =
            travel.nearest_reachable_among(places, drive.goal)) {
      cell = projected;
      drive.goal = nav.center(*projected);
      drive.arrival = drive.goal;
      drive.reachable = true;
    }
  }
  const Index2 end = drive.reachable ? *cell : travel.nearest_reachable(drive.goal);
  if (!drive.reachable) drive.arrival = nav.center(end);
  drive.length = travel.distance(end);
  return drive;
}

}  // namespace

PlacedViews stop_candidates(const CandidateSite& site, const CandidateParams& /*params*/) {
  if (site.grid == nullptr || !site.robot || !site.robot->sensor_pose) {
    throw std::invalid_argument(
        "stops are a ground robot's, found in its map: explore an office (vantage explore --scene "
        "office-...); to plan from a map alone use frontier");
  }
  const OccupancyGrid& grid = *site.grid;
  const GroundRobot& robot = *site.robot;
  const NavigationGrid nav = NavigationGrid::from_map(grid, robot.navigation);
  const TravelMap travel(nav, robot.position);
  PlacedViews out;  // NOTE: travel between stops, where asked, is the straight line
  for (const FrontierRegion& region : frontier_regions(grid, robot.frontier)) {
    const Drive drive = drive_to(region, grid.spec(), travel, robot.project_stops);
    const bool visited =
        std::any_of(robot.visited.begin(), robot.visited.end(),
                    [&](const auto& p) { return (p - drive.arrival).norm() < robot.min_move; });
    if (visited) continue;
    // NOTE: the robot faces the way it drives; a stop where it stands keeps its heading.
    const Eigen::Vector2d way = drive.goal - robot.position;
    const double yaw = way.norm() > 1e-9 ? std::atan2(way.y(), way.x()) : robot.yaw;
    out.poses.push_back(robot.sensor_pose(drive.goal.x(), drive.goal.y(), yaw));
    out.drives.push_back(drive);
  }
  return out;
}

}  // namespace vantage
