#pragma once
/// @file
/// The steps of read_manifest past its sensor and region: where the clouds come from (listed,
/// found beside the manifest, a TUM RGB-D folder (`tum`), a recording (`recording`)), their poses
/// (manifest_poses.cpp), and the checks depth images need.

#include <filesystem>
#include <optional>
#include <vector>

#include "vantage/io/manifest.hpp"
#include "vantage/io/yaml_reader.hpp"

namespace vantage::detail {

/// What read_clouds found beside Manifest::clouds, one element a cloud.
struct ManifestEntries {
  /// The YAML entry of each listed cloud, for its pose and its errors; none for a cloud found in
  /// the folder or read from a TUM folder or a recording.
  std::vector<std::optional<YamlField>> entries;
  /// Clouds posed as they were read (a TUM folder's ground truth, a recording's tf).
  std::vector<bool> posed;

  /// Where cloud `i`'s problem is reported: its entry, else `root`.
  const YamlField& at(std::size_t i, const YamlField& root) const {
    return entries[i] ? *entries[i] : root;
  }
};

/// The manifest's clouds: those `clouds` lists, or those of `tum` or `recording`, or else every
/// .pcd and .ply file in `manifest_folder`, sorted by name.
ManifestEntries read_clouds(const YamlField& root, const std::filesystem::path& manifest_folder,
                            const ManifestReadOptions& options, Manifest& manifest);

/// Poses the clouds: by `trajectory` (matched by order or time stamp), else each cloud by its
/// own `pose`, as read, by its PCD's VIEWPOINT, from the table (the first) or by registration (a
/// later one).
void read_poses(const YamlField& root, const ManifestEntries& clouds, Manifest& manifest);

/// Reads the `tum` key ({folder, every, max_time_difference}): the folder's depth frames become
/// the manifest's clouds, each with its ground-truth pose, or marked pose_from_registration when
/// it has none; `sensor.depth` defaults to the format's (5000 units a metre, 0 invalid).
void read_tum_key(const YamlField& tum, const std::filesystem::path& manifest_folder,
                  const ManifestReadOptions& options, Manifest& manifest);

/// Reads the `recording` key ({file, topic, fixed_frame, every, max_time_difference}): the
/// topic's frames become the manifest's clouds, with their points, each with its pose from tf, or
/// marked pose_from_registration when tf gives none.
void read_recording_key(const YamlField& recording, const std::filesystem::path& manifest_folder,
                        const ManifestReadOptions& options, Manifest& manifest);

/// With any depth image among the clouds: intrinsics, `sensor.depth` and the optical frame are
/// required (each missing one fails at `root`).
void check_depth_images(const YamlField& root, const Manifest& manifest);

}  // namespace vantage::detail
