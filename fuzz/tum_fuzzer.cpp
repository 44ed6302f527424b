// libFuzzer harness: a TUM RGB-D folder's depth.txt (read_tum_rgbd; the frames it names are
// missing, which must be refused as any other problem is).
#include "fuzz/harness.hpp"
#include "vantage/io/tum_rgbd.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = vantage::fuzz::write_input(data, size, "depth.txt");
  vantage::fuzz::expect_clean([&] { vantage::read_tum_rgbd(path.parent_path()); });
  vantage::fuzz::expect_clean([&] { vantage::read_tum_rgbd(path.parent_path(), {.every = 3}); });
  return 0;
}
