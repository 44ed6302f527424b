#pragma once
/// @file
/// Simulated NBV exploration, scan by scan (§5.1): scan from the current view with a noisy pose,
/// register, segment, integrate, predict every candidate's gain, move to the best.

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "vantage/perception/mapper.hpp"
#include "vantage/planner/planner.hpp"
#include "vantage/sim/scene.hpp"

namespace vantage {

/// Settings of one exploration run.
struct ExplorationConfig {
  PlannerConfig planner;   ///< method, alpha, evaluation; greedy_reference is forced on
  MapperConfig mapper;     ///< ICP, table segmentation, integration
  int scans = 10;          ///< N, the number of scans to take (the first included)
  double min_gain = 0.0;   ///< stop early once the best predicted gain falls below this
  int start = 0;           ///< index into the scene's start poses
  std::uint64_t seed = 1;  ///< sensor noise, pose noise and random choice
  /// Error of the robot's belief after each move (x, y, yaw), replacing the scene's; the first
  /// scan's pose defines the map frame and is exact. Default: 2 cm, 2 cm, 2 degrees.
  std::optional<sim::PoseNoise> pose_noise = sim::PoseNoise{0.02, 0.02, deg2rad(2.0)};

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// Wall time of each stage of one scan [s].
struct StageTimes {
  double scan = 0.0;
  double register_scan = 0.0;
  double segment = 0.0;
  double integrate = 0.0;
  double plan = 0.0;  ///< the decision that chose this scan's view
};

/// Everything recorded after one scan.
struct ScanRecord {
  int scan = 0;   ///< 1-based
  int view = -1;  ///< candidate index taken (-1: a start pose not on the ring)
  Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();  ///< true pose
  std::optional<double> predicted_gain;         ///< under the method (none for the first scan)
  std::optional<double> greedy_predicted_gain;  ///< under greedy, same view
  std::size_t actual_gain = 0;                  ///< cells that left the unobserved set
  std::size_t reentered = 0;                    ///< cells that came back into it
  std::size_t unobserved = 0;                   ///< unobserved cells after the scan
  double coverage = 0.0;           ///< observed share of the observable surface, in [0, 1]
  double pose_error_before = 0.0;  ///< translation error of the believed pose [m]
  double pose_error_after = 0.0;   ///< ... after ICP [m]
  double yaw_error_before = 0.0;   ///< rotation error of the believed pose [rad]
  double yaw_error_after = 0.0;    ///< ... after ICP [rad]
  std::size_t points = 0;
  std::size_t object_points = 0;
  StageTimes seconds;
};

/// A finished run.
struct ExplorationResult {
  std::vector<ScanRecord> scans;
  std::vector<Eigen::Isometry3d> candidates;  ///< the candidate poses of the scene
  std::string stop_reason;
  std::size_t observable_cells = 0;  ///< the coverage denominator
};

/// Called after each scan, for live progress.
using ScanCallback = std::function<void(const ScanRecord&, int total)>;

/// Runs one exploration of a simulated scene and returns its records and the final mapper.
ExplorationResult explore(const sim::Scene& scene, const ExplorationConfig& config, Mapper& mapper,
                          const ScanCallback& on_scan = {});

/// The mapper settings a scene calls for (table segmentation on for table tops).
MapperConfig default_mapper_config(const sim::Scene& scene);

}  // namespace vantage
