// libFuzzer harness: the PCD reader (read_point_cloud and read_cloud_viewpoint on a `.pcd`).
#include "fuzz/harness.hpp"
#include "vantage/io/cloud_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = vantage::fuzz::write_input(data, size, "cloud.pcd");
  vantage::fuzz::expect_clean([&] { vantage::read_point_cloud(path); });
  vantage::fuzz::expect_clean(
      [&] { vantage::read_point_cloud(path, vantage::CloudReadOptions{.skip_non_finite = true}); });
  vantage::fuzz::expect_clean([&] { vantage::read_cloud_viewpoint(path); });
  return 0;
}
