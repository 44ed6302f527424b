#pragma once
/// @file
/// Candidate views for an arm-mounted sensor (issue 26): rings of views over a table at several
/// radii and elevations, each looking at the region of interest's centre, kept where the arm
/// can reach them. Travel between them is the sensor's straight-line path.

#include <Eigen/Geometry>
#include <limits>
#include <vector>

namespace vantage {

/// An arm's reachability rule: a view is reachable when its sensor lies within `reach` of `base`.
struct ArmReach {
  Eigen::Vector3d base = Eigen::Vector3d::Zero();          ///< the arm's base [m]
  double reach = std::numeric_limits<double>::infinity();  ///< [m]
};

/// The hemisphere of views and the arm's reach.
struct HemisphereConfig {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< point every view looks at [m]
  std::vector<double> radii = {0.6, 0.8, 1.0};       ///< distances from the centre [m]
  double min_elevation = 0.2617993877991494;  ///< lowest ring above the centre's horizon, 15° [rad]
  double max_elevation = 1.3089969389957472;  ///< highest ring, 75° [rad]
  int elevations = 4;                         ///< rings per radius, evenly spaced in elevation
  /// Arc between neighbouring views of a ring: a ring of radius r cos(e) holds
  /// ceil(2 pi r cos(e) / spacing) views, at least 3 [m].
  double spacing = 0.15;
  Eigen::Vector3d base = Eigen::Vector3d::Zero();  ///< the arm's base [m]
  /// Views farther than this from `base` are dropped (infinity: every view is reachable) [m].
  double reach = std::numeric_limits<double>::infinity();

  /// Throws std::invalid_argument naming the field; also when the spacing makes more than
  /// kMaxCandidateViews views (vantage/util/limits.hpp).
  void validate() const;

  /// Elevation of ring `k` of a radius [rad].
  double elevation(int k) const;
  /// Views on ring `k` of `radius`: ceil(2 pi radius cos(e) / spacing), at least 3.
  double ring_views(double radius, int k) const;
  /// Views of every ring before the reach drops any.
  double view_count() const;
};

/// The reachable views, ordered by radius, then elevation (low to high), then azimuth (from +x,
/// counter-clockwise), each looking at the centre with its y axis level. Throws
/// std::invalid_argument when the reach holds none of them, naming the reach, the base and the
/// nearest view's distance.
std::vector<Eigen::Isometry3d> hemisphere_poses(const HemisphereConfig& config);

}  // namespace vantage
