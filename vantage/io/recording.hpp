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
  /// A damaged recording (RecordingDamage) gives the whole frames before its damage, said in
  /// Recording::salvage, rather than being refused.
  bool salvage = false;
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

/// A recording's frames, and with `salvage`, the damage they were read before.
struct Recording {
  std::vector<RecordingFrame> frames;
  std::optional<RecordingSalvage> salvage;  ///< the recording was damaged: what was kept
  /// The camera's, from the first sensor_msgs/CameraInfo on the camera_info topic, if any.
  std::optional<PinholeIntrinsics> intrinsics;
};

/// The frames of `options.topic` in `path` (an image's after all its messages are read, with the
/// latest camera info stamped at or before it, else the first) (`.bag`: ROS 1; `.mcap`: MCAP), read
/// whole through read_input_file (a recording file). Throws std::runtime_error "path: what" in one
/// line: a topic with no message (naming the topics there are), of another type, a message that
/// does not decode (its number, topic and what), a file that is neither format, a fixed_frame tf
/// does not know (naming the frames it does), a damaged file (where, and the last whole frame
/// before it; unless `options.salvage`, and there is one); std::invalid_argument for bad options.
Recording read_recording(const std::filesystem::path& path, const RecordingOptions& options);

/// What a recording alone needs to be planned from (issue 53: `vantage plan FILE.bag --topic T`).
struct RecordingAloneOptions {
  RecordingOptions read;  ///< the topic, which frames, salvage
  /// [m] the region of interest; nothing: the posed frames' points' extent, a cell wider each way.
  std::optional<Eigen::AlignedBox3d> roi = std::nullopt;
  /// [m] nothing: suited to the sensor's range (recording_resolution).
  std::optional<double> resolution = std::nullopt;
};

/// The resolution for a sensor that sees as far as `max_range` [m]: a 200th of it, rounded down
/// to 1, 2 or 5 times a power of ten (2.5 m: 0.01 m; 5 m: 0.02 m; 30 m: 0.1 m) [m].
double recording_resolution(double max_range);

/// The manifest a recording alone gives, as read_manifest would read one that named it
/// (`recording:`): its frames posed by tf (a first frame tf does not pose defines the world; a
/// later one is placed by registration), and
/// - the sensor: the CameraInfo's intrinsics (the camera_info topic beside the topic), else the
///   symmetric field of view that holds every point; its range the nearest and farthest point,
///   rounded out to 0.1 m; the frame `optical` when the frames' frame_id ends in
///   "optical_frame" or the topic holds depth images, else `x_forward` (REP 103);
/// - the roi and the resolution as `options` gives them, else as documented there;
/// - no table segmentation, no ICP (tf poses the frames).
/// Throws as read_recording, and std::runtime_error "path: what" for a region too large for a
/// grid at the resolution (naming --roi and --resolution) or frames with no point.
Manifest manifest_for_recording(const std::filesystem::path& path,
                                const RecordingAloneOptions& options);

}  // namespace vantage
