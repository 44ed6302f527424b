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

/// Renames a finished temporary file or folder into place, replacing nothing partially.
void commit_atomically(const std::filesystem::path& temporary, const std::filesystem::path& path);

}  // namespace vantage
