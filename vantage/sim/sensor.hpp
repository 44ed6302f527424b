#pragma once
/// @file
/// Simulated depth sensors: a tilting scanning range finder (the PR2's Hokuyo) and an RGB-D
/// camera (the Kinect), their ray patterns and noise.

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "vantage/views/frustum.hpp"

namespace vantage::sim {

/// How a sensor lays out its rays.
enum class SensorType {
  /// A line scanner tilted through a range of angles: beams at equal angular steps within each
  /// line, lines at equal tilt steps. Noise is along the beam.
  kRangeFinder,
  /// A pinhole depth camera: one ray through each pixel's centre. Noise is on the depth along the
  /// optical axis.
  kRgbd,
};

std::string_view to_string(SensorType type);
/// Parses "range_finder" or "rgbd"; throws std::invalid_argument naming the value.
SensorType parse_sensor_type(std::string_view name);

/// Gaussian noise whose standard deviation grows with distance d (range along the beam for a
/// range finder, depth along the optical axis for an RGB-D camera):
/// sigma(d) = sigma + sigma_quadratic * (d - reference_range)^2.
///
/// The Kinect's axial noise is about 0.0012 + 0.0019 (d - 0.4)^2 m (Nguyen, Izadi and Lovell,
/// 2012), which is the kinect preset.
struct RangeNoise {
  double sigma = 0.0;            ///< constant part [m]
  double sigma_quadratic = 0.0;  ///< [1/m]
  double reference_range = 0.0;  ///< [m]

  double sigma_at(double d) const {
    return sigma + sigma_quadratic * (d - reference_range) * (d - reference_range);
  }
  bool enabled() const { return sigma > 0.0 || sigma_quadratic > 0.0; }
  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// A sensor's rays, range limits and noise.
struct SensorConfig {
  std::string name = "kinect";
  SensorType type = SensorType::kRgbd;
  SensorFov fov;     ///< field of view and range limits: exactly the frustum its points lie in
  int width = 640;   ///< RGB-D: pixel columns
  int height = 480;  ///< RGB-D: pixel rows
  double angular_resolution = deg2rad(0.25);  ///< range finder: step between beams [rad]
  double tilt_resolution = deg2rad(0.25);     ///< range finder: step between lines [rad]
  RangeNoise noise;
  int sweep_steps = 8;  ///< yaw steps of a 360° sweep

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// The PR2's tilting Hokuyo UTM-30LX as the table top uses it: 90° x 45° at 0.25° steps (360
/// beams x 180 lines), 0.1 m to 3 m, sigma 2 mm along the beam.
SensorConfig hokuyo_sensor();
/// A Kinect: 640 x 480 pixels over 57° x 43°, 0.5 m to 3.5 m, axial noise growing with depth
/// (RangeNoise), 8 yaw steps of 45° per 360° sweep.
SensorConfig kinect_sensor();
/// "hokuyo" or "kinect"; throws std::invalid_argument listing the names for another.
SensorConfig builtin_sensor(std::string_view name);
std::vector<std::string> builtin_sensor_names();

/// The unit ray directions of one scan in the sensor frame (x forward, y left, z up), in a
/// fixed order: row by row (line by line), left to right as the sensor sees it.
///
/// Every direction lies inside the field of view of `SensorFov`: |y| <= x tan(h_fov / 2) and
/// |z| <= x tan(v_fov / 2).
std::vector<Eigen::Vector3d> ray_directions(const SensorConfig& sensor);

}  // namespace vantage::sim
