#pragma once
/// @file
/// Reading a scene file's values (scene_file.cpp, docs/scenes.md): numbers with their defaults,
/// lengths and coordinates within the limits the docs state (util/limits.hpp), poses.

#include <Eigen/Geometry>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "vantage/io/yaml_reader.hpp"
#include "vantage/sim/geometry.hpp"
#include "vantage/sim/scene.hpp"

namespace vantage::sim::detail {

/// `map[key]` as a number, or `fallback` when the key is absent.
double number_or(const YamlField& map, std::string_view key, double fallback);
/// The same, a number > 0.
double positive_or(const YamlField& map, std::string_view key, double fallback);
/// The same, a number >= 0.
double non_negative_or(const YamlField& map, std::string_view key, double fallback);

/// Refuses coordinates beyond kMaxWorldCoordinate (docs/robustness.md): a scene that reaches
/// them would be refused by the simulated world mid-run.
void require_in_world(const YamlField& f, std::span<const double> v);

/// A length: a number in (0, kMaxWorldCoordinate] m.
double length(const YamlField& f);

/// [x, y, z], each a length.
Eigen::Vector3d lengths(const YamlField& f);

/// [x, y, z] or [x, y, z, roll, pitch, yaw] with angles in degrees.
Eigen::Isometry3d parse_pose(const YamlField& f);

/// An object's mesh: a built-in `model` or a `file` (relative to `base_dir`), with its `scale`.
Shape read_mesh_shape(const YamlField& f, const std::string& label,
                      const std::filesystem::path& base_dir);

/// The `units` map: only {length: m, angle: deg}; fails naming the key otherwise.
void check_units(const YamlField& f);

/// A scene file of `kind: object` (docs/objects.md): its objects under its protocol, placed by
/// object_scene; fails naming the key for a bad one.
Scene parse_object_file(const YamlField& root, const std::filesystem::path& base_dir);

}  // namespace vantage::sim::detail
