// The files of a sweep folder (detail/sweep_files.hpp).

#include "vantage/experiment/detail/sweep_files.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <bit>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "vantage/experiment/build_info.hpp"
#include "vantage/sim/generate.hpp"
#include "vantage/sim/object_scene.hpp"

namespace vantage::detail {
namespace fs = std::filesystem;

/// FNV-1a (64 bits) over `text`, continued from `h`.
std::uint64_t fnv1a(std::string_view text, std::uint64_t h) {
  for (const char c : text) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
  return h;
}

/// FNV-1a continued over a number's 8 bytes, the low one first, so a hash is the same on any host.
std::uint64_t fnv1a_bits(std::uint64_t bits, std::uint64_t h) {
  for (int k = 0; k < 8; ++k) h = (h ^ ((bits >> (8 * k)) & 0xffU)) * 0x100000001b3ULL;
  return h;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot read", path.string()));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The file in a sweep folder that holds the settings its trials were run with.

/// The field of sweep.json that holds each scene's content hash, by scene name (scene_hash).

/// A scene's content: FNV-1a (64 bits) over its scene file's text and the solids it loads to
/// (each shape's kind, its mesh's vertices and triangles, its sphere), as "fnv1a64:" and 16 hex
/// digits. A changed scene file, or a changed model file it names, gives another hash.
std::string scene_hash(std::string_view text, const sim::Scene& scene) {
  std::uint64_t h = fnv1a(text);
  auto number = [&h](double v) { h = fnv1a_bits(std::bit_cast<std::uint64_t>(v), h); };
  auto count = [&h](std::size_t n) { h = fnv1a_bits(n, h); };
  count(scene.shapes.size());
  for (const sim::Shape& shape : scene.shapes) {
    count(shape.kind.size());
    h = fnv1a(shape.kind, h);
    count(shape.mesh_world.vertices.size());
    for (const Eigen::Vector3d& v : shape.mesh_world.vertices) {
      for (int k = 0; k < 3; ++k) number(v[k]);
    }
    count(shape.mesh_world.triangles.size());
    for (const Eigen::Vector3i& t : shape.mesh_world.triangles) {
      for (int k = 0; k < 3; ++k) count(static_cast<std::uint32_t>(t[k]));
    }
    count(shape.sphere ? 1 : 0);
    if (shape.sphere) {
      for (int k = 0; k < 3; ++k) number(shape.sphere->center[k]);
      number(shape.sphere->radius);
    }
  }
  return fmt::format("fnv1a64:{:016x}", h);
}

/// What every trial of one folder must share, so that its files can be resumed and merged: the
/// settings that change a trial's rows besides the scene, method, a and start in its key.
nlohmann::json trial_settings(const BenchConfig& config) {
  const ExplorationConfig& e = config.exploration;
  const MapperConfig& m = e.mapper;
  return {
      {"scans", e.scans},
      {"seed", e.seed},
      {"min_gain", e.min_gain},
      {"revisit", e.revisit},
      {"greedy_reference", e.planner.greedy_reference},
      {"evaluation", to_string(e.planner.gain.evaluation)},
      {"search", e.planner.search ? to_string(*e.planner.search) : "default"},
      {"sample", 1 << e.planner.sequence.sample_bits},
      {"swept_rays", e.planner.swept_rays},
      {"epsilon", e.planner.gain.epsilon},
      {"lambda", e.planner.lambda},
      {"integration", to_string(m.integration.mode)},
      {"hole_filling", m.integration.hole_filling.enabled},
      {"icp", m.register_scans},
      {"segmentation", m.segment_table},
      {"mapper_from_scene", config.mapper_from_scene},
      {"observability_alphas", e.observability.alphas},
      {"observability_recency", e.observability.recency},
      {"project_stops", e.office.project_stops},
      {"candidates", e.candidates},
      {"coverage_tolerance", e.coverage_tolerance.cells},
      {"coverage_tolerance_m", e.coverage_tolerance.metres},
      {"views", e.views.views},
      {"view_radius", e.views.radius},
      {"object",
       {{"radius", config.objects.object_radius},
        {"view_radius", config.objects.view_radius},
        {"views", config.objects.views},
        {"resolution", config.objects.resolution},
        {"sensor", config.objects.sensor}}},
      {"hemisphere_spacing", e.hemisphere.spacing},
      {"hemisphere_radii", e.hemisphere.radii},
      {"arm", e.arm ? nlohmann::json{{"base", {e.arm->base.x(), e.arm->base.y(), e.arm->base.z()}},
                                     {"reach", e.arm->reach}}
                    : nlohmann::json(nullptr)},
      {"horizon", e.planner.sequence.horizon},
      {"travel_weight", e.planner.sequence.travel_weight},
      {"shortlist", e.planner.sequence.shortlist}};
}

/// trial_settings, the binary's version and commit, the paper's a that auto and the methods' own
/// a start from, and for a sweep of generated piles which ones (their names and files say the
/// rest): a folder holds one set of piles. Each scene's content is kept beside them
/// (scene_hashes). The options that change no row (--jobs, --threads, --shard, --out,
/// --no-plots, --max-memory, --max-work) are not kept, so that shards and reruns share them.
nlohmann::json sweep_settings(const BenchConfig& config) {
  nlohmann::json settings = trial_settings(config);
  settings["version"] = std::string(build_version());
  settings["commit"] = std::string(build_commit());
  settings["paper_alpha"] = config.paper_alpha;
  if (config.generated > 0) {
    settings["generated"] = {{"count", config.generated},
                             {"objects", config.pile.objects},
                             {"first_seed", config.pile.seed}};
  }
  return settings;
}

/// A sweep folder's copy of each generated pile's scene file.

/// The content hash of each scene of a sweep, named and generated (scene_hash), by scene name.
nlohmann::json scene_hashes(const BenchConfig& config) {
  nlohmann::json hashes = nlohmann::json::object();
  const std::vector<std::string> builtin = sim::builtin_scene_names();
  for (const std::string& source : config.scenes) {
    const bool named = std::find(builtin.begin(), builtin.end(), source) != builtin.end();
    // NOTE: an object's mesh is in the loaded solids the hash covers; its file is not re-read.
    const std::string text = named                           ? sim::builtin_scene_text(source)
                             : sim::is_object_source(source) ? std::string()
                                                             : read_file(source);
    const sim::Scene scene = sim::load_scene(source, config.objects);
    hashes[scene.name] = scene_hash(text, scene);
  }
  for (const sim::PileConfig& pile : bench_piles(config)) {
    hashes[sim::pile_name(pile)] =
        scene_hash(sim::pile_scene_yaml(sim::generate_pile(pile)), sim::pile_scene(pile));
  }
  return hashes;
}

/// The files ending in `extension` in a folder's `folder`/ (scenes/ or yardstick/), by file name.
std::map<std::string, fs::path> scene_files(const fs::path& dir, const char* folder,
                                            std::string_view extension) {
  std::map<std::string, fs::path> files;
  const fs::path scenes = dir / folder;
  if (!fs::is_directory(scenes)) return files;
  for (const auto& entry : fs::directory_iterator(scenes)) {
    if (entry.path().extension() == extension) {
      files[entry.path().filename().string()] = entry.path();
    }
  }
  return files;
}

/// The settings a folder's trials were run with, or null when it has none yet.
nlohmann::json read_settings(const fs::path& dir) {
  const fs::path path = dir / kSettingsFile;
  if (!fs::exists(path)) return nullptr;
  nlohmann::json settings;
  try {
    settings = nlohmann::json::parse(read_file(path));
  } catch (const nlohmann::json::parse_error& e) {
    // NOTE: said without the library's "[json.exception.parse_error.101]" prefix.
    throw std::runtime_error(fmt::format("{}: not a sweep settings file: not valid JSON at byte {}",
                                         path.string(), e.byte));
  }
  if (!settings.is_object()) {
    throw std::runtime_error(
        fmt::format("{}: not a sweep settings file: not a JSON object", path.string()));
  }
  return settings;
}

/// Throws std::invalid_argument naming the first setting in which `found` (from `where`) differs
/// from `wanted`, the scenes' hashes aside (require_same_scenes).
void require_same_settings(const nlohmann::json& found, const nlohmann::json& wanted,
                           const fs::path& where, std::string_view remedy) {
  if (!found.contains("commit")) {
    throw std::invalid_argument(fmt::format(
        "{}: written before sweep.json recorded the binary (version, commit) and the scenes' "
        "content, so its trials cannot be checked against this run's; {}",
        where.string(), remedy));
  }
  for (const auto& [key, value] : wanted.items()) {
    if (key == kScenesKey) continue;
    if (!found.contains(key) || found[key] != value) {
      throw std::invalid_argument(
          fmt::format("{}: its trials were run with {} = {}, not {}; {}", where.string(), key,
                      found.contains(key) ? found[key].dump() : "(unset)", value.dump(), remedy));
    }
  }
}

/// Throws std::invalid_argument naming the first scene that both `found` (from `where`) and
/// `wanted` hash, with another content.
void require_same_scenes(const nlohmann::json& found, const nlohmann::json& wanted,
                         const fs::path& where, std::string_view remedy) {
  const nlohmann::json scenes = found.value(kScenesKey, nlohmann::json::object());
  for (const auto& [name, hash] : wanted.items()) {
    if (scenes.contains(name) && scenes[name] != hash) {
      throw std::invalid_argument(
          fmt::format("{}: its trials were run in another scene '{}' (content {}, not {}); {}",
                      where.string(), name, scenes[name].dump(), hash.dump(), remedy));
    }
  }
}

/// Throws std::invalid_argument naming the first field in which the settings of two folders
/// differ (a setting, the binary, or the content of a scene both hold), and both folders.
void require_same_sweep(const nlohmann::json& a, const fs::path& a_dir, const nlohmann::json& b,
                        const fs::path& b_dir) {
  auto differ = [&](const std::string& field, const nlohmann::json& in_a,
                    const nlohmann::json& in_b) {
    throw std::invalid_argument(fmt::format(
        "bench merge: {} differs: {} in {}, {} in {}; only sweeps of the same settings, binary "
        "and scenes can be merged",
        field, in_a.is_null() ? "(unset)" : in_a.dump(), (a_dir / kSettingsFile).string(),
        in_b.is_null() ? "(unset)" : in_b.dump(), (b_dir / kSettingsFile).string()));
  };
  // NOTE: both ways, so a setting one folder has and the other lacks is a difference too.
  std::vector<std::string> keys;
  for (const auto& [key, value] : a.items()) keys.push_back(key);
  for (const auto& [key, value] : b.items()) {
    if (!a.contains(key)) keys.push_back(key);
  }
  for (const std::string& key : keys) {
    if (key == kScenesKey) continue;
    const nlohmann::json in_a = a.value(key, nlohmann::json(nullptr));
    const nlohmann::json in_b = b.value(key, nlohmann::json(nullptr));
    if (in_a != in_b) differ(key, in_a, in_b);
  }
  const nlohmann::json scenes_a = a.value(kScenesKey, nlohmann::json::object());
  const nlohmann::json scenes_b = b.value(kScenesKey, nlohmann::json::object());
  for (const auto& [name, hash] : scenes_a.items()) {
    if (scenes_b.contains(name) && scenes_b[name] != hash) {
      differ(fmt::format("the content of scene '{}'", name), hash, scenes_b[name]);
    }
  }
}

/// `settings` with the scenes of `more` it lacks added to its scenes' hashes.
nlohmann::json with_scenes(nlohmann::json settings, const nlohmann::json& more) {
  nlohmann::json& scenes = settings[kScenesKey];
  if (!scenes.is_object()) scenes = nlohmann::json::object();
  const nlohmann::json more_scenes = more.value(kScenesKey, nlohmann::json::object());
  for (const auto& [name, hash] : more_scenes.items()) {
    if (!scenes.contains(name)) scenes[name] = hash;
  }
  return settings;
}

/// Trial files in a folder's trials/, by key.
std::map<std::string, fs::path> trial_files(const fs::path& dir) {
  std::map<std::string, fs::path> files;
  const fs::path trials = dir / "trials";
  if (!fs::is_directory(trials)) return files;
  for (const auto& entry : fs::directory_iterator(trials)) {
    if (entry.path().extension() == ".csv") files[entry.path().stem().string()] = entry.path();
  }
  return files;
}

}  // namespace vantage::detail
