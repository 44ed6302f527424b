#pragma once
/// @file
/// How far the sensor travels between two views: the rule of the robot or arm that carries it.
/// Each candidate set (candidate_sets.hpp) names the rule its views are travelled by.

#include <Eigen/Core>
#include <vector>

namespace vantage {

/// Travel between two sensor positions under the carrier's rule [m].
struct TravelRule {
  enum class Kind {
    kStraightLine,  ///< an arm: the sensor's straight-line path
    /// A robot walking around a table: the arc between the two bearings about `center` at
    /// `radius`, plus the change in distance from `center` (horizontal).
    kRingWalk,
    /// A sensor kept on a view sphere around an object (SCVP, MA-SCVP): the great-circle arc
    /// between the two directions from `center` at `radius`, plus the change in distance from
    /// `center`; never through the object.
    kSphereArc,
  };
  Kind kind = Kind::kStraightLine;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< kRingWalk, kSphereArc: the centre [m]
  double radius = 1.0;                               ///< kRingWalk, kSphereArc: the radius [m]

  /// Travel from `from` to `to` [m].
  double operator()(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;
  /// Points along the path the rule measures from `from` to `to`, both included, at most `step`
  /// apart [m]: the segment; the horizontal arc about `center` (the ring walk), its height and
  /// distance from `center` changing evenly along it; the great-circle arc about `center` (the
  /// view sphere), its distance from `center` changing evenly, never through the object. For
  /// views at the rule's radius its length is operator()'s, within the chords' shortfall.
  /// Throws std::invalid_argument for a step that is not positive.
  std::vector<Eigen::Vector3d> path(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                    double step = 0.02) const;
  /// What the rule measures, in words, for the result files beside the figures.
  const char* describe() const;
};

}  // namespace vantage
