#pragma once
/// @file
/// Meshes from files (PLY, OBJ, STL, OFF through assimp), the bunny's and teapot's JavaScript
/// data, and the scanned models built in by name.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

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

/// Names of the scanned models built in: "bunny", "dragon", "teapot".
std::vector<std::string> builtin_model_names();
/// Whether `name` is one of them.
bool is_builtin_model(std::string_view name);

/// Folder that holds the fetched models: $VANTAGE_MODELS_DIR, else the source tree's
/// `.cache/models` (filled by `make deps` or scripts/fetch-models.sh).
std::filesystem::path models_dir();

/// A built-in scanned model, normalised: turned from its y-up frame to z-up, centred over the
/// local origin in x and y, resting on z = 0, and scaled so that its largest extent is 1 (so a
/// scene's `scale` is the model's largest size in metres).
///
/// Throws std::invalid_argument for an unknown name (listing the known ones), and
/// std::runtime_error when the model's file is missing, saying to run `make deps` or
/// scripts/fetch-models.sh.
TriangleMesh load_builtin_model(std::string_view name,
                                const std::filesystem::path& dir = models_dir());

/// Normalises a y-up mesh as load_builtin_model describes.
TriangleMesh normalize_y_up(const TriangleMesh& mesh);

}  // namespace vantage::sim
