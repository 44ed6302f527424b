// libFuzzer harness: a ROS 1 bag (read_recording on a `.bag`, and every message decoded as a
// PointCloud2 and as a TFMessage, whatever its type says).
#include "fuzz/harness.hpp"
#include "fuzz/recording_harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  vantage::fuzz::recording_input(data, size, "recording.bag", &vantage::read_rosbag,
                                 &vantage::index_rosbag);
  return 0;
}
