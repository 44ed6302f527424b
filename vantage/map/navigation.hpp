#pragma once
/// @file
/// Where a robot on the floor can go (§5.2, §5.3.1): a 2D navigation grid from the 3D map, its
/// obstacles inflated by the robot's footprint, shortest travel distances (Dijkstra from the
/// robot to every cell, A* to one goal), and the nearest reachable place when a goal is not
/// reachable (the paper's fallback: drive as close as possible and scan there).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "vantage/map/grid_spec.hpp"
#include "vantage/map/occupancy_grid.hpp"

namespace vantage {

/// Integer cell coordinates (x, y) of a navigation grid.
using Index2 = Eigen::Vector2i;

/// Settings of the navigation grid.
struct NavigationConfig {
  /// Side of the robot's square base (the PR2's) [m]. A cell is blocked when an obstacle cell's
  /// centre lies within half of it (the inscribed circle) of the cell's centre.
  double footprint = 0.668;
  /// Obstacles are the map's cells whose centres lie in [min_height, max_height]: above what the
  /// base drives over (and above the floor's own hits and their range noise), below the top of
  /// the robot [m].
  double min_height = 0.15;
  double max_height = 1.4;  ///< [m]
  /// Unobserved cells in the band block (true) or are free (false). Free by default: a robot
  /// must plan into the unknown to explore it.
  bool unknown_blocks = false;

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// A 2D grid over the floor: one cell per (x, y) column of a 3D grid, each an obstacle or not,
/// and blocked where the robot's base cannot stand.
class NavigationGrid {
 public:
  /// From obstacle flags (1 = obstacle), x fastest then y, inflated by half the footprint.
  /// Throws std::invalid_argument when sizes disagree or a value is not usable.
  NavigationGrid(const Eigen::Vector2d& origin, double resolution, const Index2& dims,
                 std::vector<std::uint8_t> obstacles, double footprint);

  /// From the 3D map: a column is an obstacle where a cell in the height band is occupied (or
  /// unobserved, if `config.unknown_blocks`).
  static NavigationGrid from_map(const OccupancyGrid& grid, const NavigationConfig& config);

  /// From a 3D occupancy mask (1 = occupied, by linear index), e.g. the ground truth's.
  static NavigationGrid from_occupancy(const GridSpec& spec, std::span<const std::uint8_t> occupied,
                                       const NavigationConfig& config);

  /// The obstacles of both grids, inflated by `a`'s footprint: e.g. where a robot that plans on
  /// its map can drive in the true world. Throws std::invalid_argument when the grids' geometry
  /// differs.
  static NavigationGrid combine(const NavigationGrid& a, const NavigationGrid& b);

  const Eigen::Vector2d& origin() const { return origin_; }  ///< min corner of cell (0, 0) [m]
  double resolution() const { return resolution_; }          ///< [m]
  const Index2& dims() const { return dims_; }
  double footprint() const { return footprint_; }  ///< [m]
  std::size_t size() const { return obstacle_.size(); }

  bool contains(const Index2& c) const {
    return c.x() >= 0 && c.y() >= 0 && c.x() < dims_.x() && c.y() < dims_.y();
  }
  std::size_t linear(const Index2& c) const {
    return static_cast<std::size_t>(c.x()) + static_cast<std::size_t>(dims_.x()) * c.y();
  }
  Index2 unravel(std::size_t i) const {
    return {static_cast<int>(i % static_cast<std::size_t>(dims_.x())),
            static_cast<int>(i / static_cast<std::size_t>(dims_.x()))};
  }
  /// The cell holding p, or nothing outside the grid.
  std::optional<Index2> cell_of(const Eigen::Vector2d& p) const;
  /// Centre of a cell [m].
  Eigen::Vector2d center(const Index2& c) const {
    return origin_ + (c.cast<double>().array() + 0.5).matrix() * resolution_;
  }

  bool obstacle(std::size_t i) const { return obstacle_[i] != 0; }
  /// An obstacle, or too close to one for the robot's base.
  bool blocked(std::size_t i) const { return blocked_[i] != 0; }

 private:
  Eigen::Vector2d origin_;
  double resolution_;
  Index2 dims_;
  double footprint_;
  std::vector<std::uint8_t> obstacle_;
  std::vector<std::uint8_t> blocked_;
};

/// Shortest travel distances from one start to every cell of a navigation grid: 8-connected
/// moves between cell centres (orthogonal: resolution, diagonal: sqrt(2) resolution; a diagonal
/// move needs both cells beside it passable, so paths never cut a corner).
///
/// Passable cells are those not blocked, plus the non-obstacle cells within half the footprint
/// of the start: the robot stands there, so a new obstacle seen nearby must not trap it.
class TravelMap {
 public:
  /// Dijkstra from the cell holding `start` (or, outside the grid, the nearest cell).
  TravelMap(const NavigationGrid& nav, const Eigen::Vector2d& start);

  const NavigationGrid& grid() const { return nav_; }
  Index2 start() const { return nav_.unravel(start_); }
  /// Travel distance to a cell; +infinity where it cannot be reached [m].
  double distance(const Index2& c) const { return distance_[nav_.linear(c)]; }
  bool reachable(const Index2& c) const;
  /// The cell centres from the start's to c (both included); empty when c is unreachable.
  std::vector<Eigen::Vector2d> path_to(const Index2& c) const;
  /// The reachable cell whose centre is nearest to p (ties to the lower index): the goal itself
  /// when it is reachable, else the fallback.
  Index2 nearest_reachable(const Eigen::Vector2d& p) const;
  /// Of `places` (e.g. the cells of a frontier region), the one in a reachable cell whose centre
  /// is nearest p (ties to the earlier place); nothing when none is reachable. A frontier
  /// centroid can fall inside furniture; the region's own reachable cell nearest it is a stop on
  /// the frontier, where the paper's fallback (nearest_reachable) may end far from it.
  std::optional<Index2> nearest_reachable_among(std::span<const Eigen::Vector2d> places,
                                                const Eigen::Vector2d& p) const;

 private:
  NavigationGrid nav_;
  std::size_t start_;
  std::vector<double> distance_;
  std::vector<std::uint32_t> parent_;
};

/// Where a drive to a goal ends.
struct NavigationPath {
  bool reached = false;  ///< false: the goal was not reachable (fallback)
  Eigen::Vector2d end =
      Eigen::Vector2d::Zero();          ///< the goal, or the reachable place nearest it [m]
  std::vector<Eigen::Vector2d> points;  ///< cell centres from the start's to the end's [m]
  double length = 0.0;                  ///< travel distance along `points` [m]
};

/// A* (octile heuristic, exact for these moves) from start to goal. When the goal is not
/// reachable (blocked, outside the grid, or cut off), the path leads to the reachable cell
/// nearest the goal instead, with `reached` false.
NavigationPath find_path(const NavigationGrid& nav, const Eigen::Vector2d& start,
                         const Eigen::Vector2d& goal);

}  // namespace vantage
