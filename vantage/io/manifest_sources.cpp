#include "vantage/io/detail/manifest_sources.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

#include "vantage/io/input_file.hpp"
#include "vantage/io/recording.hpp"
#include "vantage/io/tum_rgbd.hpp"
#include "vantage/util/text.hpp"

namespace vantage::detail {
namespace fs = std::filesystem;
namespace {

bool is_cloud_file(const fs::path& path) {
  const std::string ext = lower_extension(path);
  return ext == ".pcd" || ext == ".ply";
}

bool is_depth_image(const fs::path& path) { return lower_extension(path) == ".png"; }

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

/// The clouds `clouds` lists, each a .pcd, .ply or .png file that can be read.
ManifestEntries read_listed_clouds(const YamlField& clouds, const fs::path& folder,
                                   Manifest& manifest) {
  ManifestEntries out;
  const std::vector<YamlField> items = clouds.items();
  if (items.empty()) clouds.fail("is empty");
  for (const YamlField& entry : items) {
    entry.allow_keys({"file", "pose", "stamp"});
    const YamlField file = entry.at("file");
    ManifestCloud cloud;
    cloud.file = (folder / file.text()).lexically_normal();
    if (!is_cloud_file(cloud.file) && !is_depth_image(cloud.file)) {
      file.fail(cat("'", cloud.file.string(), "' is not a .pcd, .ply or .png file"));
    }
    if (const std::string why =
            input_file_problem(cloud.file, is_depth_image(cloud.file) ? InputKind::kDepthImage
                                                                      : InputKind::kPointCloud);
        !why.empty()) {
      file.fail(cat(cloud.file.string(), ": ", why));
    }
    if (const auto stamp = entry.get("stamp")) cloud.stamp = stamp->number();
    manifest.clouds.push_back(cloud);
    out.entries.push_back(entry);
  }
  return out;
}

/// Every .pcd and .ply file in `folder`, sorted by name, when the manifest lists none.
void find_folder_clouds(const YamlField& root, const fs::path& folder, Manifest& manifest) {
  std::error_code error;
  for (const auto& item : fs::directory_iterator(folder.empty() ? fs::path(".") : folder, error)) {
    if (!is_cloud_file(item.path())) continue;
    // NOTE: an entry named as a cloud that is no file (a folder, a FIFO) is said by name, not
    // skipped to be found missing later as "N poses but M clouds" (issue 53).
    if (const std::string why = input_file_problem(item.path(), InputKind::kPointCloud);
        !why.empty()) {
      root.fail_as("clouds", cat("missing, so the folder's .pcd and .ply files are taken, and ",
                                 item.path().string(), " ", why));
    }
    {
      ManifestCloud cloud;
      cloud.file = item.path().lexically_normal();
      manifest.clouds.push_back(cloud);
    }
  }
  std::sort(manifest.clouds.begin(), manifest.clouds.end(),
            [](const ManifestCloud& a, const ManifestCloud& b) {
              return a.file.filename().string() < b.file.filename().string();
            });
  if (manifest.clouds.empty()) {
    root.fail_as("clouds",
                 cat("missing, and the folder ", folder.string(), " holds no .pcd or .ply file"));
  }
}

}  // namespace

ManifestEntries read_clouds(const YamlField& root, const fs::path& manifest_folder,
                            const ManifestReadOptions& options, Manifest& manifest) {
  ManifestEntries out;
  const auto tum = root.get("tum");
  const auto recording = root.get("recording");
  if (tum || recording) {
    const YamlField& key = tum ? *tum : *recording;
    if (tum && recording) key.fail("give a TUM folder or a recording, not both");
    if (root.has("clouds")) key.fail("give clouds, a TUM folder or a recording, not two");
    if (root.has("trajectory")) key.fail("its poses come with it: give no trajectory");
    if (tum) {
      read_tum_key(*tum, manifest_folder, options, manifest);
    } else {
      read_recording_key(*recording, manifest_folder, options, manifest);
    }
    for (const ManifestCloud& cloud : manifest.clouds) {
      out.posed.push_back(!cloud.pose_from_registration);
    }
  } else if (options.every || options.topic) {
    root.fail_as("",
                 "--every and --topic choose frames of a TUM folder or a recording, and the "
                 "manifest names neither (tum, recording)");
  } else if (const auto clouds = root.get("clouds")) {
    out = read_listed_clouds(*clouds, manifest_folder, manifest);
  } else {
    find_folder_clouds(root, manifest_folder, manifest);
  }
  out.entries.resize(manifest.clouds.size());
  out.posed.resize(manifest.clouds.size());
  return out;
}

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
