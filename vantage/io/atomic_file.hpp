#pragma once
/// @file
/// Result files that are written whole or not at all.

#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

namespace vantage {

/// Writes `path` by calling `write` on a temporary file beside it, then renaming it into place.
/// On any error (an exception from `write`, a failed stream, a failed rename) the temporary file
/// is removed, `path` is left as it was, and std::runtime_error names the path.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(std::ostream&)>& write);

/// Writes `content` to `path` atomically.
void write_atomically(const std::filesystem::path& path, std::string_view content);

/// Writes the folder `dir` by calling `fill` on a temporary sibling folder, then renaming it into
/// place, so the folder appears whole or not at all. `dir` must not exist or be an empty folder
/// (it is replaced). On any error the temporary folder is removed, `dir` is left as it was, and
/// the exception propagates as std::invalid_argument or std::runtime_error whose message names
/// `dir`, not the temporary folder.
void write_folder_atomically(const std::filesystem::path& dir,
                             const std::function<void(const std::filesystem::path&)>& fill);

}  // namespace vantage
