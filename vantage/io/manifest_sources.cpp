#include "vantage/io/detail/manifest_sources.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string_view>

#include "vantage/io/input_file.hpp"
#include "vantage/io/recording.hpp"
#include "vantage/io/tum_rgbd.hpp"
#include "vantage/util/text.hpp"

namespace vantage::detail {
namespace {

/// The sequence's key's `every` (1 when absent), or the command line's, which wins.
int every_of(const YamlField& key, const ManifestReadOptions& options) {
  int every = 1;
  if (const auto given = key.get("every")) every = given->integer(1, 1'000'000);
  if (options.every) {
    if (*options.every < 1) key.fail_as("every", cat("--every must be >= 1, got ", *options.every));
    every = *options.every;
  }
  return every;
}

/// The sequence's key's `max_time_difference` [s], or `fallback`.
double max_dt_of(const YamlField& key, double fallback) {
  const auto given = key.get("max_time_difference");
  return given ? given->positive() : fallback;
}

/// A sequence's frames: `read` (its options, every and max_time_difference from `key` or the
/// command line) of the path `key.path_key` names, resolved into `source`; what `reader` throws
/// fails at that key.
template <class Options, class Reader>
auto read_sequence(const YamlField& key, std::string_view path_key,
                   const std::filesystem::path& manifest_folder, const ManifestReadOptions& options,
                   Options read, std::optional<std::filesystem::path>& source, Reader reader) {
  read.every = every_of(key, options);
  read.max_time_difference = max_dt_of(key, read.max_time_difference);
  const YamlField path = key.at(path_key);
  source = (manifest_folder / path.text()).lexically_normal();
  try {
    return reader(*source, read);
  } catch (const std::runtime_error& e) {
    path.fail(e.what());
  }
}

}  // namespace

void read_tum_key(const YamlField& tum, const std::filesystem::path& manifest_folder,
                  const ManifestReadOptions& options, Manifest& manifest) {
  tum.allow_keys({"folder", "every", "max_time_difference"});
  const std::vector<TumFrame> frames = read_sequence(
      tum, "folder", manifest_folder, options, TumReadOptions{}, manifest.tum, &read_tum_rgbd);
  for (const TumFrame& frame : frames) {
    ManifestCloud cloud;
    cloud.file = frame.file;
    cloud.stamp = frame.stamp;
    // NOTE: marks a frame without ground truth; read_manifest places it (the first frame from
    // the table, a later one by registration).
    cloud.pose_from_registration = !frame.T_world_cloud;
    if (frame.T_world_cloud) cloud.T_world_cloud = *frame.T_world_cloud;
    manifest.clouds.push_back(cloud);
  }
  if (!manifest.depth) manifest.depth = DepthEncoding{.units_per_metre = 5000.0, .invalid = 0};
}

void read_recording_key(const YamlField& recording, const std::filesystem::path& manifest_folder,
                        const ManifestReadOptions& options, Manifest& manifest) {
  recording.allow_keys(
      {"file", "topic", "camera_info", "fixed_frame", "every", "max_time_difference"});
  RecordingOptions read;
  if (manifest.depth) read.depth = *manifest.depth;  // an image topic's; else ROS's millimetres
  if (const auto info = recording.get("camera_info")) read.camera_info = info->text();
  if (const auto topic = recording.get("topic")) read.topic = topic->text();
  if (options.topic) read.topic = *options.topic;
  if (read.topic.empty()) recording.fail_as("recording.topic", "missing (or give --topic)");
  if (const auto frame = recording.get("fixed_frame")) read.fixed_frame = frame->text();
  read.salvage = options.salvage;
  Recording frames = read_sequence(recording, "file", manifest_folder, options, read,
                                   manifest.recording, &read_recording);
  manifest.salvage = std::move(frames.salvage);
  for (RecordingFrame& frame : frames.frames) {
    ManifestCloud cloud;
    char stamp[32];
    std::snprintf(stamp, sizeof(stamp), "%.6f", frame.stamp);
    cloud.file = cat(manifest.recording->string(), "@", stamp);
    cloud.stamp = frame.stamp;
    cloud.pose_from_registration = !frame.T_fixed_cloud;  // NOTE: as read_tum_key marks it
    if (frame.T_fixed_cloud) cloud.T_world_cloud = *frame.T_fixed_cloud;
    cloud.non_finite = frame.non_finite;
    cloud.points = std::make_shared<const PointCloud>(std::move(frame.points));
    manifest.clouds.push_back(std::move(cloud));
  }
}

void check_depth_images(const YamlField& root, const Manifest& manifest) {
  const auto image =
      std::find_if(manifest.clouds.begin(), manifest.clouds.end(),
                   [](const ManifestCloud& c) { return lower_extension(c.file) == ".png"; });
  if (image == manifest.clouds.end()) return;
  const std::string name = image->file.filename().string();
  const YamlField sensor = root.at("sensor");
  if (!manifest.intrinsics) {
    sensor.fail_as("sensor.intrinsics",
                   cat("missing: a depth image (", name, ") needs the camera's intrinsics"));
  }
  if (!manifest.depth) {
    sensor.fail_as("sensor.depth", cat("missing: a depth image (", name,
                                       ") needs its scale (units a metre: 1000 for millimetres, "
                                       "5000 for TUM RGB-D) and its invalid value"));
  }
  if (manifest.frame != CloudFrame::kOptical) {
    sensor.fail_as("sensor.frame",
                   cat("must be optical: a depth image (", name, ") is in the camera's frame"));
  }
}

}  // namespace vantage::detail
