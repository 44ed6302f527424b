#pragma once
/// @file
/// The scanned models built in by name (the bunny, the dragon, the teapot): where they are
/// fetched to, and each loaded from its file and normalised.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "vantage/sim/geometry.hpp"

namespace vantage::sim {

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
