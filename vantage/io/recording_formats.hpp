#pragma once
/// @file
/// The two recording formats, read from their public specifications (issue 38): ROS 1 bags
/// (format 2.0, wiki.ros.org/Bags/Format/2.0) and MCAP (mcap.dev/spec), as ROS 2 records by
/// default since Iron. Each gives its messages in the order they are stored, with the topic and
/// type of each. (Debian's librosbag-dev cannot be used from CMake: its pkg-config file requires
/// a pluginlib.pc that no package installs, and its CMake package runs ament's Python at
/// configure time.)

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include "vantage/io/ros_messages.hpp"

namespace vantage {

/// One message of a recording, as stored.
struct RecordedMessage {
  std::string_view topic;
  std::string_view type;  ///< "sensor_msgs/PointCloud2" (ROS 1), "sensor_msgs/msg/PointCloud2"
  RosEncoding encoding = RosEncoding::kRos1;
  double log_time = 0.0;  ///< [s] when it was recorded
  std::string_view data;  ///< the serialized message
};

/// Called with each message; the views live until it returns.
using MessageVisitor = std::function<void(const RecordedMessage&)>;

/// Reads a ROS 1 bag (format 2.0) held in `bytes`: every message of every chunk, in order.
/// Chunks stored with "none" compression only; a bz2 or lz4 chunk is refused naming its
/// compression. Throws FormatError with one line saying what is wrong and at which byte.
void read_rosbag(std::string_view bytes, const MessageVisitor& visit);

/// Reads an MCAP file held in `bytes`: every message, in chunks (uncompressed, zstd or lz4) or
/// not, in order. Messages of an encoding other than CDR (ROS 2) are given with their channel's
/// topic and schema name, and the caller decides. Throws FormatError as above.
void read_mcap(std::string_view bytes, const MessageVisitor& visit);

}  // namespace vantage
