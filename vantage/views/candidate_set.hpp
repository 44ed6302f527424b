#pragma once
/// @file
/// What every candidate set is built from and what it gives: the one signature the registry
/// (candidate_sets.hpp) holds for each set. A set's builder lives in its own file (ring.cpp,
/// hemisphere.cpp, sphere.cpp, frontier.cpp, stops.cpp, listed.cpp).

#include <Eigen/Geometry>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "vantage/map/navigation.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/views/frontier.hpp"
#include "vantage/views/hemisphere.hpp"
#include "vantage/views/ring.hpp"
#include "vantage/views/sphere.hpp"
#include "vantage/views/travel.hpp"

namespace vantage {

/// A ground robot exploring a building (the stops set, §5.2): where it believes it stands, what it
/// drives through, where it has stopped, and where its sensor sits.
struct GroundRobot {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  ///< believed position on the floor [m]
  double yaw = 0.0;                                    ///< believed heading [rad]
  NavigationConfig navigation;                         ///< what blocks it on the map
  FrontierConfig frontier;                             ///< the frontier regions it drives to
  std::vector<Eigen::Vector2d> visited;                ///< the stops taken [m]
  double min_move = 0.5;  ///< a stop this close to one taken is not offered again [m]
  /// An unreachable frontier centroid moves to its region's reachable cell nearest it (else the
  /// robot drives to the map's nearest reachable place, the paper's fallback).
  bool project_stops = true;
  /// The sensor's pose for the robot standing at (x, y) heading yaw [m, rad] (its mount).
  std::function<Eigen::Isometry3d(double x, double y, double yaw)> sensor_pose;
};

/// Where the views are placed: what the world says, from a scene or from a map.
struct CandidateSite {
  Eigen::Vector3d target = Eigen::Vector3d::Zero();  ///< the point the views look at [m]
  Eigen::AlignedBox3d region;      ///< the region of interest, for the sets' default sizes [m]
  std::optional<RingConfig> ring;  ///< a scene's own ring (table tops), else default_ring(region)
  std::optional<SphereConfig> sphere;   ///< a scene's own view sphere (objects)
  std::optional<ArmReach> arm;          ///< the arm that carries the sensor (hemisphere); none: any
  const OccupancyGrid* grid = nullptr;  ///< the map, for sets found in it (frontier, stops)
  std::optional<GroundRobot> robot;     ///< the robot that drives to the views (stops)
};

/// What a user may say of a set; each set reads the fields it knows, 0 or empty is its default.
struct CandidateParams {
  double radius = 0.0;  ///< ring, sphere, view-sphere: distance from the target; hemisphere: the
                        ///< middle of three radii 0.75 r, r, 1.25 r [m]
  int views = 0;        ///< ring: positions x yaw offsets; sphere, view-sphere: views
  double height = std::numeric_limits<double>::quiet_NaN();  ///< ring: the sensor height [m]
  /// hemisphere: its rings' radii, elevations and spacing, overriding `radius`; its centre and
  /// reach are the site's (target, arm).
  std::optional<HemisphereConfig> hemisphere;
  /// frontier: the sensor's height band [m]; none: every height.
  std::optional<std::pair<double, double>> band;
  std::vector<Eigen::Isometry3d> listed;  ///< file: the user's poses (T_world_sensor)
};

/// A ground robot's drive to a view, planned on its map (stops).
struct Drive {
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();     ///< where the view stands [m]
  Eigen::Vector2d arrival = Eigen::Vector2d::Zero();  ///< the goal, or the nearest reachable place
  double length = 0.0;     ///< along the map's shortest path from the robot [m]
  bool reachable = false;  ///< false: the robot can only get close (the paper's fallback)
};

/// A set's views and how the sensor travels between them.
struct PlacedViews {
  std::vector<Eigen::Isometry3d> poses;  ///< T_world_sensor of each view
  TravelRule travel;
  std::string note = {};  ///< one line on what was built or left out (frontier), or empty
  /// Per view, the robot's drive to it when the set plans it on the map (stops); empty: the
  /// travel from the robot follows `travel`.
  std::vector<Drive> drives = {};
};

// The builders the registry's rows name, each defined in its set's own file.
/// ring.cpp: the site's ring (or default_ring(region)), radius, height and views overridden.
PlacedViews ring_candidates(const CandidateSite& site, const CandidateParams& params);
/// hemisphere.cpp: rings at radii `radii` (or 0.75, 1, 1.25 x `radius`), within the arm's reach.
PlacedViews hemisphere_candidates(const CandidateSite& site, const CandidateParams& params);
/// sphere.cpp: a band of a sphere above the target (0 to 80 degrees), 50 views by default.
PlacedViews sphere_candidates(const CandidateSite& site, const CandidateParams& params);
/// sphere.cpp: the whole sphere around an object, 32 views by default, travel on the sphere.
PlacedViews view_sphere_candidates(const CandidateSite& site, const CandidateParams& params);
/// frontier.cpp: four level views at each frontier region's centroid in a known free cell.
PlacedViews frontier_candidates(const CandidateSite& site, const CandidateParams& params);
/// stops.cpp: a ground robot's next stops: the frontier regions' centroids not yet visited, each
/// with its drive on the map; none when no frontier is left.
PlacedViews stop_candidates(const CandidateSite& site, const CandidateParams& params);
/// listed.cpp: the user's poses as given.
PlacedViews listed_candidates(const CandidateSite& site, const CandidateParams& params);

}  // namespace vantage
