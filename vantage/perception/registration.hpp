#pragma once
/// @file
/// Registration of a new scan to the accumulated cloud with ICP, starting from the robot's noisy
/// pose estimate (§4.2), and the pose error that shows what it bought.

#include <Eigen/Geometry>
#include <string_view>

#include "vantage/map/point_cloud.hpp"

namespace vantage::perception {

/// The error ICP minimises.
enum class IcpMetric {
  /// Squared distance between paired points (Besl & McKay; the paper's [25]) in every stage.
  kPointToPoint,
  /// Point to point in the coarse stages, then the squared distance along the reference's normal
  /// in the stages that pair within 2 × max_correspondence_distance.
  kPointToPlane,
};

std::string_view to_string(IcpMetric metric);
/// Parses "point_to_point" or "point_to_plane"; throws std::invalid_argument naming the value.
IcpMetric parse_icp_metric(std::string_view name);

/// Settings of scan registration. ICP runs in stages: the first pairs points up to
/// `initial_correspondence_distance` apart, each further stage halves the distance, and the last
/// uses `max_correspondence_distance`; a stage pairing within d aligns the scan thinned to voxels
/// of max(voxel_size, d / 2).
///
/// The defaults suit a table top (7.8 mm cells, a robot's pose off by a few cm and degrees):
/// 8 cm covers most of how far such an error moves a point 1-2 m away, 1 cm is about a cell,
/// and 1 cm voxels keep a scan to ~10k points. On simulated table-top scans (IcpStudy in
/// tests/perception/registration_test.cpp; docs/perception.md) they bring guesses 5 cm / 6.4°
/// off to 0.70 mm / 0.029° mean with 1 mm range noise, and to 2.05 mm / 0.077° with 3 mm.
struct IcpConfig {
  IcpMetric metric = IcpMetric::kPointToPlane;
  double max_correspondence_distance = 0.01;      ///< [m] pairing distance of the final stage
  double initial_correspondence_distance = 0.08;  ///< [m] of the first stage; it must exceed how
                                                  ///< far the guess displaces a point
  int max_iterations = 30;                        ///< per stage
  double transformation_epsilon = 1e-10;    ///< [m²] converged when one iteration moves the scan
                                            ///< by less than its square root (and turns it by less
                                            ///< than acos(1 - epsilon))
  double euclidean_fitness_epsilon = 1e-6;  ///< converged when the mean squared pair distance
                                            ///< changes by less than this fraction
  double voxel_size = 0.004;   ///< [m] both clouds are downsampled to this voxel; 0 = not at all
  int normal_neighbours = 12;  ///< neighbours per normal of the reference (point to plane)

  /// Throws std::invalid_argument naming the field (e.g. "icp.voxel_size").
  void validate() const;
};

/// What registration found.
struct IcpResult {
  Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();  ///< the corrected pose
  /// The last stage met a convergence criterion (transformation or fitness epsilon) within
  /// max_iterations. When false, T_world_sensor is still ICP's last estimate, or the guess when
  /// too few points could be paired; the caller decides whether to trust it.
  bool converged = false;
  /// Mean squared distance [m²] from the aligned (downsampled) scan's points to their nearest
  /// reference point, over the points within max_correspondence_distance; infinity if none.
  double fitness = 0.0;
  /// Share of the aligned (downsampled) scan's points within max_correspondence_distance of the
  /// reference: the overlap ICP worked with.
  double inlier_fraction = 0.0;
  int iterations = 0;  ///< over all stages
};

/// Aligns a scan to the accumulated reference cloud, starting from the noisy pose
/// `T_world_sensor_guess`, and returns the corrected pose (§4.2). Deterministic.
///
/// Throws std::invalid_argument for a bad config, an empty scan or reference, or a non-finite
/// point (naming the cloud and index).
IcpResult register_scan(const PointCloud& points_sensor,
                        const Eigen::Isometry3d& T_world_sensor_guess,
                        const PointCloud& reference_world, const IcpConfig& config);

/// Silences what PCL prints to stderr on its own, such as ICP's "Not enough correspondences
/// found": Vantage reports each outcome itself (IcpResult::converged, the segmentation's result).
/// PCL's verbosity is a process-wide setting, so this is the application's call; the vantage CLI
/// makes it.
void silence_pcl_console();

/// Distance between two poses.
struct PoseError {
  double translation = 0.0;  ///< [m] between the origins
  double rotation = 0.0;     ///< [rad] angle of the relative rotation, in [0, π]
};

/// The error of pose `a` against pose `b` (e.g. before or after ICP against the true pose).
PoseError pose_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

}  // namespace vantage::perception
