#pragma once
/// @file
/// A simulated experiment's world: geometry, grid, sensor and its mount, start poses, candidate
/// views and pose noise, read from a YAML scene file (docs/scenes.md) or built in by name.

#include <Eigen/Geometry>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vantage/map/grid_spec.hpp"
#include "vantage/sim/geometry.hpp"
#include "vantage/sim/sensor.hpp"
#include "vantage/views/hemisphere.hpp"
#include "vantage/views/ring.hpp"
#include "vantage/views/sphere.hpp"

namespace vantage::sim {

/// What kind of experiment a scene is for.
enum class SceneKind {
  kTableTop,  ///< candidate views on a ring around the table (§5.1)
  kOffice,    ///< candidate stops at frontier centroids, a 360° sweep at each (§5.2)
  /// Single objects floating on a view sphere (the field's protocol, object_scene.hpp): no table
  /// to segment, the sphere's views as candidates and starts, travel on the sphere.
  kObject,
};
std::string_view to_string(SceneKind kind);

/// Where the sensor sits on the robot. A robot stands at (x, y) on the floor, heading yaw; its
/// sensor is `height` above the floor and either aims at `target` (table top: the robot turns
/// its torso to the table) or is pitched down by `pitch` along the heading (office).
struct SensorMount {
  double height = 1.0;                               ///< sensor above the floor [m]
  bool aims_at_target = false;                       ///< true: look at target; false: use pitch
  Eigen::Vector3d target = Eigen::Vector3d::Zero();  ///< point the sensor looks at [m]
  double pitch = 0.0;                                ///< downward tilt, positive looks down [rad]

  /// Sensor pose of a robot standing at (x, y) with heading yaw [m, rad]. With a target, yaw is
  /// ignored.
  Eigen::Isometry3d sensor_pose(double x, double y, double yaw = 0.0) const;
};

/// How a robot's belief of its pose errs after a move: Gaussian on x, y and yaw, zero by default.
struct PoseNoise {
  double x = 0.0;    ///< sigma [m]
  double y = 0.0;    ///< sigma [m]
  double yaw = 0.0;  ///< sigma [rad]

  bool enabled() const { return x > 0.0 || y > 0.0 || yaw > 0.0; }
  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// The robot that carries the sensor.
struct RobotConfig {
  double footprint = 0.668;   ///< side of its square base (the PR2's) [m]
  double height = 1.4;        ///< obstacles below this height block it [m]
  double stop_spacing = 0.5;  ///< lattice of floor stops used by the office ground truth [m]
};

/// A named room of an office, for pictures and reports.
struct Room {
  std::string name;
  Eigen::AlignedBox2d area;  ///< (x, y) [m]
};

/// Everything one simulated experiment needs.
struct Scene {
  std::string name;
  std::string source;  ///< "built-in" or the YAML file's path
  SceneKind kind = SceneKind::kTableTop;
  GridSpec grid;
  SensorConfig sensor;
  SensorMount mount;
  /// Table top: the candidate views (K positions x yaw offsets around mount.target, radius from
  /// the file, height = mount.height). Unused in an office.
  RingConfig ring;
  /// Object: the view sphere its candidates and starts lie on (object_scene.hpp).
  std::optional<SphereConfig> view_sphere;
  std::vector<Eigen::Isometry3d> start_poses;  ///< T_world_sensor of each start
  /// Table top: the arm that carries the sensor over the table (the hemisphere's reachability
  /// rule, `arm:` in docs/scenes.md); none: every hemisphere view is reachable.
  std::optional<ArmReach> arm;
  PoseNoise pose_noise;
  RobotConfig robot;
  std::vector<Shape> shapes;       ///< all solids, static and objects [m]
  std::vector<Room> rooms;         ///< office rooms (their walls are among the shapes)
  Eigen::AlignedBox2d floor_area;  ///< where a robot may stand (x, y) [m]

  /// Table top: the ring's 30 candidate views; object: the view sphere's; office: none (the
  /// planner finds frontiers).
  std::vector<Eigen::Isometry3d> candidate_poses() const;
  /// The sensor's field of view (the frusta of candidates and scans).
  const SensorFov& fov() const { return sensor.fov; }
};

/// Names of the scenes built in: tabletop-1..4, office-{small,large}-{sparse,cluttered}.
std::vector<std::string> builtin_scene_names();

/// The text of a built-in scene file; throws std::invalid_argument for an unknown name.
std::string builtin_scene_text(std::string_view name);

/// A built-in scene by name, or a scene file by path; a built-in model's name or a mesh file
/// (.ply, .obj, .off, .stl) is a single object under the default protocol (object_scene.hpp). Throws std::invalid_argument with one line
/// that names the file, line and key for a bad scene (unknown key, missing key, key given twice,
/// wrong type, negative size, unknown model or sensor, a missing or corrupt mesh file), and
/// std::runtime_error when the scene is neither built in nor a readable file.
Scene load_scene(const std::string& name_or_yaml_path);

/// Parses scene YAML text; `source` names it in messages, relative mesh paths resolve against
/// `base_dir`.
Scene parse_scene(const std::string& yaml_text, const std::string& source,
                  const std::filesystem::path& base_dir);

/// RPY pose from [x, y, z, roll, pitch, yaw] [m, rad]: R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Isometry3d pose_from_xyz_rpy(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy);

/// The largest roll, pitch or yaw a pose is given with [deg]: a turn either way; more is a typo
/// (1e300 deg is no angle a person means), refused rather than wrapped.
inline constexpr double kMaxAngleDegrees = 360.0;

}  // namespace vantage::sim
