#pragma once
/// @file
/// The limits inputs are checked against where they are read (issue 39): one table, shared by the
/// CLI's options, the scene and manifest readers, the file readers and Python, and the one
/// docs/robustness.md ("Limits") states; a test holds the two equal.

#include <array>
#include <cstdint>
#include <string_view>

namespace vantage {

inline constexpr std::uintmax_t kKiB = 1024, kMiB = 1024 * kKiB, kGiB = 1024 * kMiB;

/// Largest point cloud file (PCD, PLY) read whole [bytes].
inline constexpr std::uintmax_t kMaxCloudFileBytes = 2 * kGiB;
/// Largest OctoMap file (.bt, .ot) [bytes].
inline constexpr std::uintmax_t kMaxMapFileBytes = 4 * kGiB;
/// Largest mesh file a scene names (OBJ, OFF, STL, PLY, the models' JavaScript) [bytes].
inline constexpr std::uintmax_t kMaxMeshFileBytes = 1 * kGiB;
/// Largest text file of settings: a manifest, a scene [bytes].
inline constexpr std::uintmax_t kMaxSettingsFileBytes = 16 * kMiB;
/// Largest pose file: a manifest's trajectory, `plan --candidates FILE` [bytes].
inline constexpr std::uintmax_t kMaxPoseFileBytes = 64 * kMiB;
/// Largest depth image (16-bit PNG) read whole [bytes].
inline constexpr std::uintmax_t kMaxDepthImageFileBytes = 64 * kMiB;
/// Most pixels a depth image (a PNG, a bag's Image message) may have: its decoded depths are
/// allocated [pixels].
inline constexpr std::uint64_t kMaxDepthImagePixels = 1ull << 26;
/// Largest recording (a ROS 1 bag, an MCAP file), read record by record [bytes].
inline constexpr std::uintmax_t kMaxRecordingFileBytes = 64 * kGiB;
/// Largest results file `vantage view` reads (run.json, plan.json) [bytes].
inline constexpr std::uintmax_t kMaxResultsFileBytes = 1 * kGiB;

/// Most candidate views one decision scores (a pose file, a ring, a sphere, a hemisphere): each
/// view's cells in its frustum are walked and its gain kept [views].
inline constexpr std::uint64_t kMaxCandidateViews = 100'000;
/// Most objects a scene file places (each one's mesh is built and held) [objects].
inline constexpr std::uint64_t kMaxSceneObjects = 10'000;
/// Most floor stops an office's ground truth sweeps from (the floor's area over
/// robot.stop_spacing squared); robot.stop_spacing must also be at least the grid's resolution,
/// finer stops see nothing a cell does not [stops].
inline constexpr std::uint64_t kMaxFloorStops = 20'000;

/// One row of the table, as docs/robustness.md states it.
struct Limit {
  std::string_view name;  ///< what is limited, as the docs say it
  double value;
  std::string_view unit;
};

/// Every limit above, in the docs' order.
inline constexpr std::array<Limit, 12> kLimits = {{
    {"point cloud file", static_cast<double>(kMaxCloudFileBytes / kMiB), "MiB"},
    {"OctoMap file", static_cast<double>(kMaxMapFileBytes / kMiB), "MiB"},
    {"mesh file", static_cast<double>(kMaxMeshFileBytes / kMiB), "MiB"},
    {"manifest or scene file", static_cast<double>(kMaxSettingsFileBytes / kMiB), "MiB"},
    {"pose file", static_cast<double>(kMaxPoseFileBytes / kMiB), "MiB"},
    {"results file", static_cast<double>(kMaxResultsFileBytes / kMiB), "MiB"},
    {"depth image file", static_cast<double>(kMaxDepthImageFileBytes / kMiB), "MiB"},
    {"pixels of a depth image", static_cast<double>(kMaxDepthImagePixels >> 20), "Mi pixels"},
    {"recording file", static_cast<double>(kMaxRecordingFileBytes / kMiB), "MiB"},
    {"candidate views of a decision", static_cast<double>(kMaxCandidateViews), "views"},
    {"objects of a scene", static_cast<double>(kMaxSceneObjects), "objects"},
    {"floor stops of an office's ground truth", static_cast<double>(kMaxFloorStops), "stops"},
}};

}  // namespace vantage
