#pragma once
/// @file
/// The terms of the registration's cost (registration.cpp): a correction of the guess and its
/// coordinates, the prior's information, each scan point paired with the map's planes, and the
/// directions the data constrains. Included by registration.cpp only.

#include <Eigen/Geometry>
#include <algorithm>
#include <cstddef>
#include <vector>

#include "vantage/map/point_cloud.hpp"
#include "vantage/perception/registration.hpp"
#include "vantage/perception/voxel_map.hpp"

namespace vantage::perception::detail {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// A correction of the guess: rotation `R` about the guess's sensor position `c`, then the
/// translation `t`, so p -> R (p - c) + c + t. Its coordinates x = (rotation vector, t) are what
/// the prior weighs: the odometry's error is a rotation about the sensor and a shift.
struct Correction {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();

  Vector6d coordinates() const {
    const Eigen::AngleAxisd aa(R);
    Vector6d x;
    x << aa.angle() * aa.axis(), t;
    return x;
  }
  Eigen::Vector3d apply(const Eigen::Vector3d& p, const Eigen::Vector3d& c) const {
    return R * (p - c) + c + t;
  }
};

/// One scan point's pairing at the current correction: residual along the map's normal and its
/// Jacobian with respect to (rotation about the current sensor position, translation).
struct Pair {
  bool valid = false;
  double residual = 0.0;
  Vector6d jacobian = Vector6d::Zero();
};

/// The information (inverse covariance) of the prior on a correction's coordinates.
Matrix6d prior_information(const PoseSigma& s);

/// Pairs every point of `points_world` (at the guess) moved by `correction` with the map.
std::vector<Pair> pair_up(const PointCloud& points_world, const Correction& correction,
                          const Eigen::Vector3d& c, const VoxelMap& map, double distance);

/// The projection onto the directions the data constrains. A scene without structure along a
/// direction (a plane: the shift along it, the turn about its normal) still gives its points'
/// noisy normals a small component there, and Gauss-Newton would follow that noise by as much as
/// residual / (normal tilt × lever): degrees. Directions whose information is below `ratio` of
/// the strongest are left to the prior. They are judged as motions about the scan's centroid
/// `m` (the Jacobians turn about the sensor `s`), rotations measured at the scan's radius
/// `radius` about it, so that a turn the objects' spread pins compares with a shift.
/// NOTE: the idea of Zhang, Kaess and Singh (ICRA 2016), "On degeneracy of optimization-based
/// state estimation problems".
Matrix6d constrained(const Matrix6d& H, const Eigen::Vector3d& m, const Eigen::Vector3d& s,
                     double radius, double ratio);

/// How many of `pairs` are valid.
inline std::size_t count(const std::vector<Pair>& pairs) {
  return static_cast<std::size_t>(
      std::count_if(pairs.begin(), pairs.end(), [](const Pair& p) { return p.valid; }));
}

/// The weight of each of `pairs` pairs. NOTE: neighbouring points share their map points,
/// normals and the scan's systematic errors: together they count as at most
/// `independent_points` independent measurements.
inline double independent_share(std::size_t pairs, const RegistrationConfig& config) {
  return pairs > config.independent_points
             ? static_cast<double>(config.independent_points) / static_cast<double>(pairs)
             : 1.0;
}

}  // namespace vantage::perception::detail
