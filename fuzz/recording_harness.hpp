#pragma once
/// @file
/// What the recording harnesses (ROS 1 bag, MCAP) share: the file read as `vantage plan` reads
/// it (refused, or salvaged), the container read alone with every message handed to both message
/// decoders, and its index read alone.

#include <string>
#include <string_view>

#include "fuzz/harness.hpp"
#include "vantage/io/recording.hpp"
#include "vantage/io/recording_formats.hpp"

namespace vantage::fuzz {

inline void recording_input(const std::uint8_t* data, std::size_t size, const std::string& name,
                            void (*read)(std::string_view, const MessageVisitor&),
                            RecordingIndex (*index)(std::string_view)) {
  const auto path = write_input(data, size, name);
  expect_clean([&] { read_recording(path, {.topic = "/camera/depth/points"}); });
  expect_clean([&] { read_recording(path, {.topic = "/camera/depth/image_raw"}); });
  // NOTE: a damaged recording salvaged (issue 53), and its index read alone, which never throws.
  expect_clean(
      [&] { read_recording(path, {.topic = "/camera/depth/points", .salvage = true}); });
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  for (const auto& [topic, count] : index(bytes)) sink = sink + static_cast<double>(count);
  expect_clean([&] {
    read(bytes, [](const RecordedMessage& m) {
      expect_clean([&] { decode_point_cloud2(m.data, m.encoding); });
      expect_clean([&] { decode_tf_message(m.data, m.encoding); });
      expect_clean([&] { decode_depth_image(m.data, m.encoding); });
      expect_clean([&] { decode_camera_info(m.data, m.encoding); });
    });
  });
}

}  // namespace vantage::fuzz
