#pragma once
/// @file
/// Small hand-made scenes for the simulator's tests.

#include <utility>

#include "vantage/sim/scene.hpp"

namespace vantage::sim::testing {

/// A scene with a grid around the origin, the given sensor, and no geometry yet.
inline Scene empty_scene(const SensorConfig& sensor) {
  Scene scene;
  scene.name = "test";
  scene.grid = GridSpec::centered(Eigen::Vector3d::Zero(), 0.05, {80, 80, 80});
  scene.sensor = sensor;
  return scene;
}

/// A box shape given by its min and max corners [m].
inline Shape box_shape(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  Shape s;
  s.name = "box";
  s.kind = "box";
  const Eigen::Vector3d size = hi - lo;
  const Eigen::Vector3d base(0.5 * (lo.x() + hi.x()), 0.5 * (lo.y() + hi.y()), lo.z());
  s.mesh_world = transformed(make_box(size), Eigen::Isometry3d(Eigen::Translation3d(base)));
  return s;
}

inline Shape sphere_shape(const Eigen::Vector3d& center, double radius) {
  Shape s;
  s.name = "sphere";
  s.kind = "sphere";
  s.sphere = Sphere{center, radius};
  return s;
}

/// An RGB-D sensor without noise.
inline SensorConfig quiet_rgbd(int width = 160, int height = 120) {
  SensorConfig s = kinect_sensor();
  s.width = width;
  s.height = height;
  s.noise = {};
  return s;
}

/// A range finder without noise.
inline SensorConfig quiet_range_finder() {
  SensorConfig s = hokuyo_sensor();
  s.angular_resolution = deg2rad(1.0);
  s.tilt_resolution = deg2rad(1.0);
  s.fov.max_range = 10.0;
  s.noise = {};
  return s;
}

}  // namespace vantage::sim::testing
