#pragma once
/// @file
/// A robot's recording read as a sequence of frames (issue 38): the point clouds of one topic of
/// a ROS 1 bag or an MCAP file, each with the pose tf gives its frame in a fixed frame at its
/// stamp, interpolated.

#include <Eigen/Geometry>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "vantage/io/manifest.hpp"
#include "vantage/map/point_cloud.hpp"

namespace vantage {

/// Which frames of a recording, and how they are posed.
struct RecordingOptions {
  /// A sensor_msgs/PointCloud2 topic, or a sensor_msgs/Image topic of depth images (16UC1 or
  /// mono16), each pixel one ray by depth_to_points with the camera's CameraInfo.
  std::string topic = {};
  /// The CameraInfo topic of an image topic; empty: the image topic's sibling `camera_info`
  /// (/camera/depth/image_raw: /camera/depth/camera_info).
  std::string camera_info = {};
  /// How an image topic's values map to metres: ROS's 16UC1 is millimetres.
  DepthEncoding depth = {.units_per_metre = 1000.0, .invalid = 0};
  /// tf's fixed frame (`map`, `odom`, `world`); empty: the root of the first frame's tf tree.
  std::string fixed_frame = {};
  int every = 1;  ///< the first frame and every `every`-th after it
  /// [s] the tf samples around a frame's stamp must lie this close to it (static ones always do).
  double max_time_difference = 0.1;
};

/// One frame of the recording.
struct RecordingFrame {
  double stamp = 0.0;          ///< [s] its header's
  std::string frame_id;        ///< the frame its points are in
  PointCloud points;           ///< the finite points [m]
  std::size_t non_finite = 0;  ///< points dropped (NaN marks a pixel without depth)
  /// The pose of frame_id in the fixed frame at the stamp; nothing when tf does not connect them
  /// there (no tf at all, or none within max_time_difference).
  std::optional<Eigen::Isometry3d> T_fixed_cloud;
};

/// The frames of `options.topic` in `path` (an image's after all its messages are read, with the
/// latest camera info stamped at or before it, else the first) (`.bag`: ROS 1; `.mcap`: MCAP), read
/// whole through read_input_file (a recording file). Throws std::runtime_error "path: what" in one
/// line: a topic with no message (naming the topics there are), of another type, a message that
/// does not decode (its number, topic and what), a file that is neither format;
/// std::invalid_argument for bad options.
std::vector<RecordingFrame> read_recording(const std::filesystem::path& path,
                                           const RecordingOptions& options);

}  // namespace vantage
