// libFuzzer harness: the depth image reader (read_depth_png, then one ray end per pixel).
#include "fuzz/harness.hpp"
#include "vantage/io/depth_image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = vantage::fuzz::write_input(data, size, "depth.png");
  vantage::fuzz::expect_clean([&] {
    const vantage::DepthImage image = vantage::read_depth_png(path);
    const vantage::PinholeIntrinsics k{.fx = 500.0,
                                       .fy = 500.0,
                                       .cx = (image.width - 1) / 2.0,
                                       .cy = (image.height - 1) / 2.0,
                                       .width = image.width,
                                       .height = image.height};
    vantage::depth_to_points(image, k, {.units_per_metre = 5000.0, .invalid = 0});
  });
  return 0;
}
