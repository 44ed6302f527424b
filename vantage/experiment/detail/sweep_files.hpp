#pragma once
/// @file
/// The files of a sweep folder (bench.hpp): its settings (sweep.json: what shapes a row, the
/// binary, each scene's content hash), its trial files, and the checks that keep two folders'
/// trials apart. Shared by the sweep (bench.cpp) and the merge of folders (bench.cpp).

#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "vantage/experiment/bench.hpp"
#include "vantage/sim/scene.hpp"

namespace vantage::detail {

/// FNV-1a's 64-bit offset basis.
inline constexpr std::uint64_t kFnvOffset = 0xcbf29ce484222325ULL;
/// FNV-1a (64 bits) over `text`, continued from `h`.
std::uint64_t fnv1a(std::string_view text, std::uint64_t h = kFnvOffset);

/// FNV-1a continued over a number's 8 bytes, the low one first, so a hash is the same on any host.
std::uint64_t fnv1a_bits(std::uint64_t bits, std::uint64_t h);

/// The whole of a file; throws std::runtime_error naming it when it cannot be read.
std::string read_file(const std::filesystem::path& path);

/// The file in a sweep folder that holds the settings its trials were run with.
inline constexpr const char* kSettingsFile = "sweep.json";
/// The field of sweep.json that holds each scene's content hash, by scene name (scene_hash).
inline constexpr const char* kScenesKey = "scenes";
/// A scene's content: FNV-1a (64 bits) over its scene file's text and the solids it loads to
/// (each shape's kind, its mesh's vertices and triangles, its sphere), as "fnv1a64:" and 16 hex
/// digits. A changed scene file, or a changed model file it names, gives another hash.
std::string scene_hash(std::string_view text, const sim::Scene& scene);

/// What every trial of one folder must share, so that its files can be resumed and merged: the
/// settings that change a trial's rows besides the scene, method, a and start in its key.
nlohmann::json trial_settings(const BenchConfig& config);

/// trial_settings, the binary's version and commit, the paper's a that auto and the methods' own
/// a start from, and for a sweep of generated piles which ones (their names and files say the
/// rest): a folder holds one set of piles. Each scene's content is kept beside them
/// (scene_hashes). The options that change no row (--jobs, --threads, --shard, --out,
/// --no-plots, --max-memory, --max-work) are not kept, so that shards and reruns share them.
nlohmann::json sweep_settings(const BenchConfig& config);

/// A sweep folder's copy of each generated pile's scene file.
inline constexpr const char* kScenesFolder = "scenes";
/// The content hash of each scene of a sweep, named and generated (scene_hash), by scene name.
nlohmann::json scene_hashes(const BenchConfig& config);

/// The files ending in `extension` in a folder's `folder`/ (scenes/ or yardstick/), by file name.
std::map<std::string, std::filesystem::path> scene_files(const std::filesystem::path& dir,
                                                         const char* folder = kScenesFolder,
                                                         std::string_view extension = ".yaml");

/// The settings a folder's trials were run with, or null when it has none yet.
nlohmann::json read_settings(const std::filesystem::path& dir);

/// Throws std::invalid_argument naming the first setting in which `found` (from `where`) differs
/// from `wanted`, the scenes' hashes aside (require_same_scenes).
void require_same_settings(const nlohmann::json& found, const nlohmann::json& wanted,
                           const std::filesystem::path& where, std::string_view remedy);

/// Throws std::invalid_argument naming the first scene that both `found` (from `where`) and
/// `wanted` hash, with another content.
void require_same_scenes(const nlohmann::json& found, const nlohmann::json& wanted,
                         const std::filesystem::path& where, std::string_view remedy);

/// Throws std::invalid_argument naming the first field in which the settings of two folders
/// differ (a setting, the binary, or the content of a scene both hold), and both folders.
void require_same_sweep(const nlohmann::json& a, const std::filesystem::path& a_dir,
                        const nlohmann::json& b, const std::filesystem::path& b_dir);

/// `settings` with the scenes of `more` it lacks added to its scenes' hashes.
nlohmann::json with_scenes(nlohmann::json settings, const nlohmann::json& more);

/// Trial files in a folder's trials/, by key.
std::map<std::string, std::filesystem::path> trial_files(const std::filesystem::path& dir);

}  // namespace vantage::detail
