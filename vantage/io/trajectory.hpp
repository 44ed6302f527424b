#pragma once
/// @file
/// Sensor poses on disk: TUM trajectories and checks of 4x4 rigid transforms.

#include <Eigen/Geometry>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace vantage {

/// A pose with its time stamp.
struct StampedPose {
  double stamp = 0.0;                                               ///< [s]
  Eigen::Isometry3d T_world_frame = Eigen::Isometry3d::Identity();  ///< pose of the data's frame
};

/// Largest deviation |R^T R - I| a rotation may have [-].
inline constexpr double kRotationTolerance = 1e-6;
/// Largest deviation of a TUM quaternion's norm from 1 before it is normalised; TUM files often
/// print four decimals [-].
inline constexpr double kQuaternionNormTolerance = 1e-3;

/// What is wrong with a 4x4 matrix as a rigid transform, or an empty string when nothing is:
/// a non-finite entry, a bottom row other than 0 0 0 1 (within 1e-9), a rotation that is not
/// orthonormal within kRotationTolerance, or a reflection (det R = -1).
std::string rigid_transform_problem(const Eigen::Matrix4d& m);

/// Reads a trajectory in the TUM RGB-D format: one pose per line, `timestamp tx ty tz qx qy qz
/// qw` (seconds, metres, unit quaternion, Hamilton convention, giving T_world_frame); blank
/// lines and lines starting with '#' are skipped. A quaternion whose norm is within
/// kQuaternionNormTolerance of 1 is normalised. The file is opened by read_input_file as a pose
/// file (a regular file of at most kMaxPoseFileBytes) and holds at most kMaxCandidateViews poses.
/// Throws std::runtime_error as "file:line: what".
std::vector<StampedPose> read_tum_trajectory(const std::filesystem::path& path);

/// The pose at `stamp` from poses sorted by strictly increasing stamp: a pose of that very stamp
/// as it is, else the interpolation (linear in position, spherical in rotation) between the two
/// around it, each within `max_time_difference` [s] of it; nothing when there are no such two
/// (no extrapolation). Throws std::invalid_argument when the stamps do not increase.
std::optional<Eigen::Isometry3d> interpolate_pose(const std::vector<StampedPose>& poses,
                                                  double stamp, double max_time_difference);

/// Writes a TUM trajectory (17 significant digits) atomically.
void write_tum_trajectory(const std::filesystem::path& path, const std::vector<StampedPose>& poses);

}  // namespace vantage
