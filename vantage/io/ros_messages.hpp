#pragma once
/// @file
/// The ROS messages a recording's frames and poses come in, decoded from their wire formats
/// (issue 38): ROS 1's serialization (a bag's messages) and CDR (ROS 2; an MCAP file's). Only
/// what mapping needs is kept.

#include <Eigen/Geometry>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "vantage/io/depth_image.hpp"
#include "vantage/map/point_cloud.hpp"

namespace vantage {

/// The wire format of a message.
enum class RosEncoding {
  kRos1,  ///< ROS 1 serialization: little endian, packed, strings without their terminator
  kCdr,   ///< ROS 2: an encapsulation header, then CDR (aligned, strings with a terminator)
};

/// std_msgs/Header's part Vantage uses.
struct RosHeader {
  double stamp = 0.0;    ///< [s]
  std::string frame_id;  ///< the frame the data is in
};

/// sensor_msgs/PointCloud2: the x, y, z of every point (FLOAT32 or FLOAT64 fields) [m].
struct RosCloud {
  RosHeader header;
  PointCloud points;           ///< the finite points, in order
  std::size_t non_finite = 0;  ///< points with a non-finite coordinate, dropped
};

/// geometry_msgs/TransformStamped: the pose of `child` in `header.frame_id`.
struct RosTransform {
  RosHeader header;
  std::string child;
  Eigen::Isometry3d T_parent_child = Eigen::Isometry3d::Identity();
};

/// sensor_msgs/Image of a depth camera: 16-bit depths (encoding 16UC1 or mono16).
struct RosDepthImage {
  RosHeader header;
  DepthImage image;
};

/// sensor_msgs/CameraInfo's pinhole part: K's focal lengths and principal point, the size.
struct RosCameraInfo {
  RosHeader header;
  PinholeIntrinsics intrinsics;
};

/// Decodes a sensor_msgs/Image of encoding 16UC1 or mono16 (another is refused naming it), rows
/// of `step` bytes, big- or little-endian. Throws FormatError as decode_point_cloud2 does, and for
/// more than kMaxDepthImagePixels.
RosDepthImage decode_depth_image(std::string_view message, RosEncoding encoding);

/// Decodes a sensor_msgs/CameraInfo (ROS 1 or ROS 2 field names, the same layout). Throws
/// FormatError as above, and for intrinsics PinholeIntrinsics::validate refuses.
RosCameraInfo decode_camera_info(std::string_view message, RosEncoding encoding);

/// Decodes a sensor_msgs/PointCloud2. Throws FormatError with one line saying what is wrong
/// (a field past the message's end, a count the data cannot hold, no float x, y and z fields, a
/// row or point step too small for its fields). Checks every count against the bytes left before
/// it allocates.
RosCloud decode_point_cloud2(std::string_view message, RosEncoding encoding);

/// Decodes a tf2_msgs/TFMessage (tf and tf_static). Throws FormatError as above, and for a
/// rotation that is not a unit quaternion (within 1e-3, then normalised) or a non-finite value.
std::vector<RosTransform> decode_tf_message(std::string_view message, RosEncoding encoding);

}  // namespace vantage
