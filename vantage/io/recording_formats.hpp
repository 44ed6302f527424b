#pragma once
/// @file
/// The two recording formats, read from their public specifications (issue 38): ROS 1 bags
/// (format 2.0, wiki.ros.org/Bags/Format/2.0) and MCAP (mcap.dev/spec), as ROS 2 records by
/// default since Iron. Each gives its messages in the order they are stored, with the topic and
/// type of each. (Debian's librosbag-dev cannot be used from CMake: its pkg-config file requires
/// a pluginlib.pc that no package installs, and its CMake package runs ament's Python at
/// configure time.)
///
/// Each reader checks what its format offers against what it reads (issue 53): a bag's header,
/// its index data after each chunk and its chunk info records at the end; an MCAP file's chunk
/// CRCs, its data end CRC, its message indexes, its summary's CRC and statistics, its footer and
/// closing magic; every length and size claim against the bytes there are. What fails is
/// RecordingDamage, thrown before any message of the damaged part is given.

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>

#include "vantage/io/format_parsing.hpp"
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

/// A recording that is damaged: cut short (no index, footer or closing magic; a record that runs
/// past the file's end), a CRC that does not match, a size or a count that its own index or the
/// file contradicts. Every message given before it was thrown lies before `offset()`, the first
/// byte that cannot be trusted, and was checked (`--salvage` maps them).
class RecordingDamage : public FormatError {
 public:
  RecordingDamage(std::uint64_t offset, const std::string& what)
      : FormatError(what), offset_(offset) {}
  std::uint64_t offset() const { return offset_; }  ///< [byte] of the file

 private:
  std::uint64_t offset_ = 0;
};

/// What a recording's own index (a bag's connection and chunk info records, an MCAP summary's
/// channels and statistics) says it holds, per topic; empty when there is none or it is damaged.
using RecordingIndex = std::map<std::string, std::uint64_t, std::less<>>;

/// Reads a ROS 1 bag (format 2.0) held in `bytes` (rosbag.cpp): every message of every chunk, in
/// order. Chunks stored with "none" compression only; a bz2 or lz4 chunk is refused naming its
/// compression. Throws RecordingDamage for damage and FormatError for what is not (a
/// compression or version Vantage does not read), each in one line saying what and at which byte.
void read_rosbag(std::string_view bytes, const MessageVisitor& visit);

/// Reads an MCAP file held in `bytes` (mcap.cpp): every message, in chunks (uncompressed, zstd or
/// lz4) or not, in order. Messages of an encoding other than CDR (ROS 2) are given with their
/// channel's topic and schema name, and the caller decides. Throws as read_rosbag.
void read_mcap(std::string_view bytes, const MessageVisitor& visit);

/// The messages per topic a bag's index counts (its connection and chunk info records, found by
/// its header's index_pos); empty when it has none that reads. Never throws.
RecordingIndex index_rosbag(std::string_view bytes);

/// The messages per topic an MCAP file's summary counts (its channels and statistics, found by
/// its footer); empty when it has none that reads. Never throws.
RecordingIndex index_mcap(std::string_view bytes);

}  // namespace vantage
