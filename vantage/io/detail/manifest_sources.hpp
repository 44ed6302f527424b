#pragma once
/// @file
/// Where a manifest's clouds come from besides its files: a TUM RGB-D folder (`tum`), a recording
/// (`recording`); and the checks depth images need.

#include <filesystem>

#include "vantage/io/manifest.hpp"
#include "vantage/io/yaml_reader.hpp"

namespace vantage::detail {

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
