// libFuzzer harness: an MCAP file (read_recording on a `.mcap`, and every message decoded as a
// PointCloud2 and as a TFMessage, whatever its schema says).
#include "fuzz/harness.hpp"
#include "fuzz/recording_harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  vantage::fuzz::recording_input(data, size, "recording.mcap", &vantage::read_mcap,
                                 &vantage::index_mcap);
  return 0;
}
