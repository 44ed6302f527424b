// issue 38: depth images in. A pixel is one ray end in the optical frame; bad PNGs are refused
// with one line. (The 16-bit PNGs of a real frame: tests/experiment/recordings_test.cpp.)

#include "vantage/io/depth_image.hpp"

#include <gtest/gtest.h>

#include <string>

#include "vantage/io/format_parsing.hpp"

namespace vantage {
namespace {

std::string error_of(std::string_view bytes) {
  try {
    decode_depth_png(bytes);
  } catch (const FormatError& e) {
    return e.what();
  }
  return "no error";
}

TEST(DepthImage, EachPixelWithDepthIsOneRayEnd) {
  DepthImage image{.width = 3, .height = 2, .depth = {5000, 0, 10000, 2500, 7, 65535}};
  const PinholeIntrinsics k{.fx = 2.0, .fy = 4.0, .cx = 1.0, .cy = 0.5, .width = 3, .height = 2};
  const PointCloud points = depth_to_points(image, k, {.units_per_metre = 5000.0, .invalid = 0});
  ASSERT_EQ(points.size(), 5u);  // the pixel of value 0 has no depth
  // Pixel (0, 0) at 1 m: one pixel left of the principal point over fx, half a pixel up over fy.
  EXPECT_EQ(points[0], Eigen::Vector3d(-0.5, -0.125, 1.0));
  EXPECT_EQ(points[1], Eigen::Vector3d(1.0, -0.25, 2.0));     // (2, 0) at 2 m
  EXPECT_EQ(points[2], Eigen::Vector3d(-0.25, 0.0625, 0.5));  // (0, 1) at 0.5 m
  // Rounded to float, as a PCD or PointCloud2 of the frame holds it.
  EXPECT_EQ(points[3].z(), static_cast<double>(static_cast<float>(7.0 / 5000.0)));
  EXPECT_EQ(points[4].z(), static_cast<double>(static_cast<float>(65535.0 / 5000.0)));
  // Another invalid value: 65535 has no depth, 0 is at the camera.
  EXPECT_EQ(depth_to_points(image, k, {.units_per_metre = 1000.0, .invalid = 65535}).size(), 5u);
  // The image must be the intrinsics' size; the scale positive.
  PinholeIntrinsics wide = k;
  wide.width = 4;
  wide.cx = 1.5;
  EXPECT_THROW(depth_to_points(image, wide, {}), std::invalid_argument);
  EXPECT_THROW(depth_to_points(image, k, {.units_per_metre = 0.0}), std::invalid_argument);
}

TEST(DepthImage, BadPngsAreRefusedWithOneLine) {
  EXPECT_EQ(error_of("P5\n640 480\n65535\n"),
            "not a PNG image (the first 8 bytes are not PNG's signature)");
  EXPECT_EQ(error_of(""), "not a PNG image (the first 8 bytes are not PNG's signature)");
  const std::string signature = "\x89PNG\r\n\x1a\n";
  EXPECT_EQ(error_of(signature), "a broken PNG: the file ends inside the image");
  // A header chunk whose CRC is wrong.
  const std::string ihdr = std::string("\0\0\0\x0dIHDR\0\0\x02\x80\0\0\x01\xe0\x10\0\0\0\0", 21) +
                           std::string("\0\0\0\0", 4);
  EXPECT_EQ(error_of(signature + ihdr).rfind("a broken PNG: ", 0), 0u)
      << error_of(signature + ihdr);
}

}  // namespace
}  // namespace vantage
