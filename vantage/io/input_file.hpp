#pragma once
/// @file
/// The one way every reader opens an input file (issue 39): a regular file only (a FIFO would
/// block, a device never end), at most the size its kind may have (vantage/util/limits.hpp), and,
/// where an extension can lie, the format its first bytes name.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace vantage {

/// What an input file holds, which decides the most bytes it may have.
enum class InputKind {
  kPointCloud,  ///< PCD, PLY: kMaxCloudFileBytes
  kOctomap,     ///< .bt, .ot: kMaxMapFileBytes
  kMesh,        ///< a scene's mesh: kMaxMeshFileBytes
  kSettings,    ///< a manifest, a scene: kMaxSettingsFileBytes
  kPoses,       ///< a trajectory, a candidates file: kMaxPoseFileBytes
  kResults,     ///< run.json, plan.json, sweep.json: kMaxResultsFileBytes
  kDepthImage,  ///< a 16-bit PNG: kMaxDepthImageFileBytes
  kRecording,   ///< a ROS 1 bag, an MCAP file: kMaxRecordingFileBytes
};

/// "point cloud", "OctoMap file", ...: the kind as a message says it.
std::string_view to_string(InputKind kind);

/// The most bytes a file of `kind` may have.
std::uintmax_t max_input_bytes(InputKind kind);

/// Why `path` cannot be read as a `kind`, said as what it is ("no such file", "is a FIFO, not a
/// regular file", "is 5.00 GiB, more than the 2.00 GiB a point cloud file may have"); empty when
/// it can.
std::string input_file_problem(const std::filesystem::path& path, InputKind kind);

/// The size of `path` [bytes] after input_file_problem found nothing; throws FormatError with
/// what it found.
std::uintmax_t require_input_file(const std::filesystem::path& path, InputKind kind);

/// The bytes of `path` (or its first `max_bytes`, a header) after require_input_file; never more
/// than the kind allows, even from a file that grows while it is read. Throws FormatError.
std::string read_input_file(const std::filesystem::path& path, InputKind kind,
                            std::size_t max_bytes = std::string::npos);

/// The format a file's first bytes name, as a message says it ("a PCD point cloud", "a PLY file",
/// "an OctoMap file", "an OFF mesh", "OBJ text", "ASCII STL", "JSON"); empty when they name none
/// of these.
std::string_view sniff_format(std::string_view head);

/// The extension of `path` in lower case, with its dot (".pcd"); empty when it has none.
std::string lower_extension(const std::filesystem::path& path);

}  // namespace vantage
