#pragma once
/// @file
/// A scene made castable: Embree 3 ray casting of the scene's sensor, with range and pose noise.

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "vantage/map/point_cloud.hpp"
#include "vantage/sim/scene.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage::sim {

/// Settings of a World.
struct WorldConfig {
  int num_threads = 0;  ///< 0 = all cores; scans are identical for any count

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// One simulated scan.
struct SimulatedScan {
  /// The measured points in the sensor frame (x forward, y left, z up), taken from the true pose.
  /// Rays that hit nothing within the sensor's range give no point [m].
  PointCloud points_sensor;
  Eigen::Isometry3d T_world_sensor_true = Eigen::Isometry3d::Identity();  ///< where it was
  Eigen::Isometry3d T_world_sensor_noisy =
      Eigen::Isometry3d::Identity();  ///< what the robot believes
  SensorFov fov;                      ///< the sensor's field of view and range
  std::size_t rays = 0;               ///< rays cast

  /// The frustum as the robot believes it (noisy pose).
  Frustum view() const { return Frustum(T_world_sensor_noisy, fov); }
  /// The points in the world as the robot believes them (through the noisy pose) [m].
  PointCloud points_world() const { return transform(T_world_sensor_noisy, points_sensor); }
};

/// A 360° sweep at one stop: the sensor turned about the world's z axis in equal yaw steps.
struct SimulatedSweep {
  /// One scan per step; step k is turned by 2 pi k / N from the given pose. All steps share the
  /// stop's pose error.
  std::vector<SimulatedScan> steps;
  /// All steps' points merged into the sensor frame of step 0 [m].
  PointCloud points_sensor;
  Eigen::Isometry3d T_world_sensor_true = Eigen::Isometry3d::Identity();   ///< step 0
  Eigen::Isometry3d T_world_sensor_noisy = Eigen::Isometry3d::Identity();  ///< step 0

  /// All points in the world as the robot believes them [m].
  PointCloud points_world() const { return transform(T_world_sensor_noisy, points_sensor); }
};

/// A scene loaded into Embree, ready to scan. Thread-safe for concurrent const calls.
class World {
 public:
  /// Builds the Embree scene from the scene's shapes; throws std::runtime_error when Embree
  /// fails, std::invalid_argument for a bad config or sensor.
  explicit World(Scene scene, const WorldConfig& config = {});
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  const Scene& scene() const { return scene_; }
  const WorldConfig& config() const { return config_; }

  /// A scan with the scene's sensor from the true pose T_world_sensor. The noisy pose adds the
  /// scene's pose noise (x, y, yaw) drawn from `seed`; range noise is drawn from `seed` too, so a
  /// seed gives the same scan on any number of threads.
  SimulatedScan scan(const Eigen::Isometry3d& T_world_sensor, std::uint64_t seed) const;
  /// The same with another sensor.
  SimulatedScan scan(const Eigen::Isometry3d& T_world_sensor, const SensorConfig& sensor,
                     std::uint64_t seed) const;

  /// A 360° sweep of the scene's sensor at `sensor.sweep_steps` yaw steps (office stops).
  SimulatedSweep sweep(const Eigen::Isometry3d& T_world_sensor, std::uint64_t seed) const;

  /// The poses of a sweep's steps from T_world_sensor: step k turned by 2 pi k / N about world z.
  std::vector<Eigen::Isometry3d> sweep_poses(const Eigen::Isometry3d& T_world_sensor) const;

  /// Distance along a ray to the nearest surface in [0, max_range], or nothing [m].
  std::optional<double> cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                             double max_range) const;

  /// Whether any surface lies on the ray within [0, distance] (cheaper than cast) [m].
  bool occluded(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                double distance) const;

  /// The true pose with the scene's pose noise for `seed` applied (itself when noise is off).
  Eigen::Isometry3d noisy_pose(const Eigen::Isometry3d& T_world_sensor, std::uint64_t seed) const;

 private:
  struct Embree;
  SimulatedScan scan_with(const Eigen::Isometry3d& T_true, const Eigen::Isometry3d& T_noisy,
                          const SensorConfig& sensor,
                          const std::vector<Eigen::Vector3d>& directions,
                          std::uint64_t noise_seed) const;

  Scene scene_;
  WorldConfig config_;
  std::vector<Eigen::Vector3d> directions_;  ///< the scene sensor's rays, sensor frame
  std::unique_ptr<Embree> embree_;
};

}  // namespace vantage::sim
