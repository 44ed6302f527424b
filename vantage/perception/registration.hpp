#pragma once
/// @file
/// Scan-to-map registration (§4.2) that cannot make a pose much worse than the robot's own
/// estimate: point to plane against a voxel map of what was registered so far, a robust kernel,
/// correspondence distances derived from the odometry noise model, the odometry prior in the
/// cost, and a check of the result against the prior with a fallback to the prior.

#include <Eigen/Geometry>
#include <cstddef>
#include <string_view>

#include "vantage/map/point_cloud.hpp"
#include "vantage/perception/voxel_map.hpp"

namespace vantage::perception {

/// The odometry noise model: the standard deviation of a pose guess's error, a translation along
/// the world axes and a rotation about the world axes through the sensor. The defaults are the
/// simulator's default pose noise (2 cm, 2 cm, 2°) and a small slack on what a wheeled robot
/// knows well (height, roll and pitch of its sensor mount).
struct PoseSigma {
  double x = 0.02;       ///< [m]
  double y = 0.02;       ///< [m]
  double z = 0.002;      ///< [m]
  double roll = 0.002;   ///< [rad]
  double pitch = 0.002;  ///< [rad]
  double yaw = 0.035;    ///< [rad] (2°)

  /// Throws std::invalid_argument naming the field (all must be > 0).
  void validate() const;
};

/// Settings of scan-to-map registration.
///
/// Correspondence distance (as KISS-ICP adapts its threshold to the motion model's error): the
/// first stage pairs a scan point with the nearest map point within `sigmas` × (the displacement
/// the prior allows a point at the scan's farthest range, plus `sensor_sigma`); each further
/// stage halves it, down to `min_distance`. The robust kernel's scale is a third of the stage's
/// distance.
struct RegistrationConfig {
  PoseSigma prior;              ///< the guess's uncertainty: the prior's weight and the threshold
  double sensor_sigma = 0.002;  ///< [m] noise of a point against the map's surface
  double sigmas = 3.0;          ///< the first stage's distance in standard deviations
  double min_distance = 0.015;  ///< [m] correspondence distance of the last stage
  double voxel_size = 0.01;     ///< [m] the scan is thinned to this (coarse stages: distance/4)
  int max_iterations = 15;      ///< Gauss-Newton iterations per stage, at most
  double convergence = 1e-5;    ///< a stage ends when a step is below this [m and rad]
  /// Directions of the pose whose information from the data is below this share of the
  /// strongest direction's (rotations at the scan's range) are degenerate: the data's noise is
  /// all they hold, and the prior alone decides them.
  double degenerate_ratio = 0.01;
  /// Neighbouring points share map points, normals and the scan's systematic errors: all pairs
  /// together weigh as this many independent ones against the prior.
  std::size_t independent_points = 100;
  /// The check: the correction's squared Mahalanobis distance under the prior must not exceed
  /// this (chi-square, 6 degrees of freedom, 99.9 %), ...
  double max_mahalanobis2 = 22.46;
  /// ... the last stage must pair at least this many points, ...
  std::size_t min_correspondences = 50;
  /// ... and at least this share of the scan's (thinned) points: a scan that overlaps the map
  /// less (the far side of a table, seen for the first time) rests on too few surfaces to tell a
  /// slide along its view from the truth, ...
  double min_overlap = 0.2;
  /// ... and the posterior must know the sensor's position to this (its largest standard
  /// deviation): a scan that pins its pose no better (the far side of a table, seen after the
  /// near side) is left at the guess [m].
  double max_position_sigma = 0.0025;
  /// Gauss-Newton also starts from the guess turned about the vertical through the sensor by
  /// plus and minus this many yaw sigmas; the solution of lowest posterior cost wins. 0: the
  /// guess alone.
  double start_sigmas = 2.0;
  /// ... and a solution elsewhere (further than 2 x max_position_sigma) whose cost is within this
  /// of the winner's makes the pose uncertain: the data cannot tell the two apart.
  double ambiguity_cost = 3.0;
  /// Once every start has run a stage, a start whose posterior cost is above the lowest by more
  /// than this is dropped: the finer stages pair within half the distance and less, and move a
  /// start that far behind too little to catch up, at up to max_iterations a stage each (a
  /// hand-held Kinect frame: 150 of its 184 iterations). Must be >= ambiguity_cost.
  double prune_cost = 30.0;
  int num_threads = 0;  ///< 0 = all cores; the result is the same for any count

  /// Throws std::invalid_argument naming the field (e.g. "registration.min_distance").
  void validate() const;
};

/// Why a registration's result was kept or the prior taken instead.
enum class RegistrationOutcome {
  kAccepted,        ///< the corrected pose passed the check
  kEmptyMap,        ///< nothing to register against (the first scan)
  kTooFewMatches,   ///< the last stage paired fewer than min_correspondences points or min_overlap
  kOutsidePrior,    ///< the correction is implausible under the odometry noise model
  kUncertain,       ///< the posterior does not know the position to max_position_sigma
  kWorseThanPrior,  ///< the posterior's cost is no lower at the solution than at the guess
};

std::string_view to_string(RegistrationOutcome outcome);

/// What registration found.
struct RegistrationResult {
  /// The corrected pose when accepted, else the guess.
  Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
  /// What the optimisation reached, whether or not it was accepted.
  Eigen::Isometry3d T_world_sensor_solved = Eigen::Isometry3d::Identity();
  RegistrationOutcome outcome = RegistrationOutcome::kEmptyMap;
  double mahalanobis2 = 0.0;              ///< of the solved correction under the prior
  std::size_t correspondences = 0;        ///< pairs in the last stage at the solved pose
  std::size_t points = 0;                 ///< ... of this many scan points (thinned)
  std::size_t guess_correspondences = 0;  ///< ... at the guess
  double first_distance = 0.0;            ///< [m] the first stage's correspondence distance
  int iterations = 0;                     ///< over all stages
  /// Directions of the pose (of 6) the data constrained in the last iteration; the prior alone
  /// decided the others.
  int constrained_directions = 0;
  /// [m] the posterior's standard deviation of the sensor's position along its worst axis.
  double position_sigma = 0.0;
  /// The posterior's cost (robust point to plane on the last stage's pairing, plus the prior)
  /// at the solution, and at the guess, where the prior costs nothing.
  double cost = 0.0;
  double guess_cost = 0.0;

  bool accepted() const { return outcome == RegistrationOutcome::kAccepted; }
};

/// Aligns a scan (sensor frame) to the map, starting from and weighed against the odometry's
/// guess `T_world_sensor_guess`. Deterministic for any thread count. Throws
/// std::invalid_argument for a bad config, a non-finite guess or point (naming its index).
RegistrationResult register_scan(const PointCloud& points_sensor,
                                 const Eigen::Isometry3d& T_world_sensor_guess, const VoxelMap& map,
                                 const RegistrationConfig& config);

/// Silences what PCL prints to stderr on its own, such as RANSAC's warnings: Vantage reports
/// each outcome itself. PCL's verbosity is a process-wide setting, so this is the application's
/// call; the vantage CLI makes it.
void silence_pcl_console();

/// Where a scan's points lie: their mean and covariance, enough to tell how far a pose error
/// moves them on average.
struct PointSpread {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();        ///< [m]
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< [m²]

  /// The spread of the same points in frame a, this being their spread in frame b.
  PointSpread transformed(const Eigen::Isometry3d& T_a_b) const {
    return {T_a_b * mean, T_a_b.linear() * covariance * T_a_b.linear().transpose()};
  }
};

/// The spread of `points` (none: zero).
PointSpread point_spread(const PointCloud& points);

/// Distance between two poses.
struct PoseError {
  double translation = 0.0;  ///< [m] between the origins
  double rotation = 0.0;     ///< [rad] angle of the relative rotation, in [0, π]
  /// [m] how far the scan's points land from where they belong, root mean square. What a map
  /// suffers: a sensor's position error traded for a smaller turn can bring its points closer.
  double displacement = 0.0;
};

/// The error of pose `a` against pose `b` (e.g. before or after registration against the truth).
PoseError pose_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);
/// ... and the displacement of a scan's points, taken from `b`, whose spread (in the frame both
/// poses are in) is `points_at_b`, when they are placed by `a` instead.
PoseError pose_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
                     const PointSpread& points_at_b);

}  // namespace vantage::perception
