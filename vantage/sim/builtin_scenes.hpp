#pragma once
/// @file
/// The scene files under scenes/, compiled into the library so that built-in scenes load from
/// anywhere (the build embeds them; see embed_scenes.cmake).

#include <span>
#include <string_view>

namespace vantage::sim {

/// One embedded scene file: its name (the file name without .yaml) and its text.
struct BuiltinSceneFile {
  std::string_view name;
  std::string_view text;
};

/// All embedded scene files, sorted by name.
std::span<const BuiltinSceneFile> builtin_scene_files();

}  // namespace vantage::sim
