#pragma once
/// @file
/// A TUM RGB-D data set's folder read as a sequence (issue 38): `depth.txt` lists the depth
/// frames (`timestamp file`, the file relative to the folder: `depth/*.png`, 16-bit at 5000 units
/// a metre), `groundtruth.txt`, when present, the camera's poses (TUM trajectory format, the
/// optical frame's pose in the world).

#include <Eigen/Geometry>
#include <filesystem>
#include <optional>
#include <vector>

namespace vantage {

/// One depth frame of the sequence.
struct TumFrame {
  std::filesystem::path file;  ///< the depth PNG
  double stamp = 0.0;          ///< [s]
  /// The optical frame's pose, interpolated from groundtruth.txt (interpolate_pose); nothing when
  /// the folder has none, or none within max_time_difference on both sides of the stamp.
  std::optional<Eigen::Isometry3d> T_world_cloud;
};

/// How the sequence is read.
struct TumReadOptions {
  int every = 1;                      ///< take the first frame and every `every`-th after it
  double max_time_difference = 0.02;  ///< [s] for interpolating the ground truth
};

/// Reads `folder`/depth.txt (every `options.every`-th frame, in its order) and, when present,
/// `folder`/groundtruth.txt. Every frame's file must be a readable depth image file
/// (input_file_problem). Throws std::runtime_error as "file:line: what" for a malformed line,
/// a missing frame, stamps that do not increase; "folder: what" for a folder without depth.txt or
/// without frames; std::invalid_argument for every < 1 or a non-positive max_time_difference.
std::vector<TumFrame> read_tum_rgbd(const std::filesystem::path& folder,
                                    const TumReadOptions& options = {});

}  // namespace vantage
