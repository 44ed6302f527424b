#pragma once
/// @file
/// Meshes from files (PLY, OBJ, STL, OFF through assimp) and the bunny's and teapot's JavaScript
/// data; the scanned models built in by name are builtin_models.hpp's.

#include <filesystem>

#include "vantage/sim/geometry.hpp"

namespace vantage::sim {

/// Reads every triangle of a PLY, OBJ, STL or OFF file (node transforms applied, polygons
/// triangulated) in the file's own units and frame.
///
/// The file is opened as read_input_file opens a mesh (a regular file of at most
/// kMaxMeshFileBytes); its extension must be one of these four, and its first bytes, where they
/// name a format, that one (OBJ text in `m.xyz` or `m.off` is refused, not sniffed past).
///
/// Throws std::runtime_error with one line naming the file when it is missing, cannot be parsed,
/// or holds no triangle.
TriangleMesh load_mesh(const std::filesystem::path& path);

/// Reads a mesh written as JavaScript data, `exports.positions = [[x, y, z], ...]` and
/// `exports.cells = [[i, j, k], ...]`, as the npm packages `bunny` and `teapot` ship it. The text
/// is parsed as numbers only; nothing is executed. Throws std::runtime_error naming the file and
/// the offending character offset.
TriangleMesh load_js_mesh(const std::filesystem::path& path);

}  // namespace vantage::sim
