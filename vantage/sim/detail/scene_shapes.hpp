#pragma once
/// @file
/// Reading a scene file's shapes (scene_file.cpp, docs/scenes.md) into a Scene: each fails
/// naming the key of a bad value.

#include <cstddef>
#include <filesystem>

#include "vantage/io/yaml_reader.hpp"
#include "vantage/sim/scene.hpp"

namespace vantage::sim::detail {

/// `floor` ({size, center, thickness}): a slab below z = 0, and the floor's area.
void read_floor(const YamlField& f, Scene& scene);

/// `table` ({size, height, center, top_thickness, leg_width}).
void read_table(const YamlField& f, Scene& scene);

/// `walls` ({height, thickness, segments}), `rooms` (each a box of walls) and the `doors` cut in
/// them, from the scene's `root`.
void read_walls(const YamlField& root, Scene& scene);

/// The object `objects[index]`: a box, a piece of furniture, a cylinder, a sphere or a mesh
/// (its file relative to `base_dir`), at its pose, repeated on a grid when it says so.
void read_object(const YamlField& f, std::size_t index, const std::filesystem::path& base_dir,
                 Scene& scene);

}  // namespace vantage::sim::detail
