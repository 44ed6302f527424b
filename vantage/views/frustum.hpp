#pragma once
/// @file
/// A sensor's field of view and the frustum it sweeps from a pose.

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace vantage {

/// Degrees to radians.
constexpr double deg2rad(double deg) { return deg * std::numbers::pi / 180.0; }

/// What a depth sensor sees: a rectangular (pinhole-style) field of view, cut by range.
///
/// The sensor frame looks along +x, with +y to the left and +z up (REP 103). Range is the
/// Euclidean distance from the sensor origin.
struct SensorFov {
  double h_fov = deg2rad(57.0);  ///< full horizontal field of view, in (0, pi) [rad]
  double v_fov = deg2rad(43.0);  ///< full vertical field of view, in (0, pi) [rad]
  double min_range = 0.5;        ///< [m]
  double max_range = 3.5;        ///< [m]

  /// Throws std::invalid_argument naming the field.
  void validate() const;
  bool operator==(const SensorFov&) const = default;
};

/// A candidate or actual view: a sensor pose and its field of view.
class Frustum {
 public:
  /// Validates the field of view and the pose; throws std::invalid_argument.
  Frustum(const Eigen::Isometry3d& T_world_sensor, const SensorFov& fov);
  Frustum() : Frustum(Eigen::Isometry3d::Identity(), SensorFov{}) {}

  const Eigen::Isometry3d& T_world_sensor() const { return T_world_sensor_; }
  const SensorFov& fov() const { return fov_; }
  Eigen::Vector3d origin() const { return T_world_sensor_.translation(); }

  /// Whether a world point lies inside the field of view and the range limits.
  bool contains(const Eigen::Vector3d& p_world) const {
    const Eigen::Vector3d p = T_sensor_world_ * p_world;
    if (p.x() <= 0.0) return false;
    const double r2 = p.squaredNorm();
    return r2 >= min_r2_ && r2 <= max_r2_ && std::abs(p.y()) <= p.x() * tan_h_ &&
           std::abs(p.z()) <= p.x() * tan_v_;
  }

  /// An axis-aligned box in the world that holds the whole frustum.
  Eigen::AlignedBox3d bounds() const;

 private:
  Eigen::Isometry3d T_world_sensor_;
  SensorFov fov_;
  Eigen::Isometry3d T_sensor_world_;
  double tan_h_, tan_v_, min_r2_, max_r2_;
};

}  // namespace vantage
