#include "vantage/experiment/bench.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <thread>

#include "vantage/experiment/decision_cost.hpp"
#include "vantage/experiment/results.hpp"
#include "vantage/experiment/yardstick.hpp"
#include "vantage/io/atomic_file.hpp"
#include "vantage/sim/scene.hpp"
#include "vantage/util/clock.hpp"

namespace vantage {
namespace fs = std::filesystem;
namespace {

std::uint64_t fnv1a(std::string_view text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const char c : text) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
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
constexpr const char* kSettingsFile = "sweep.json";

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
      {"candidates", to_string(e.candidates)},
      {"coverage_tolerance", e.coverage_tolerance},
      {"hemisphere_spacing", e.hemisphere.spacing},
      {"hemisphere_radii", e.hemisphere.radii},
      {"arm", e.arm ? nlohmann::json{{"base", {e.arm->base.x(), e.arm->base.y(), e.arm->base.z()}},
                                     {"reach", e.arm->reach}}
                    : nlohmann::json(nullptr)},
      {"horizon", e.planner.sequence.horizon},
      {"travel_weight", e.planner.sequence.travel_weight},
      {"shortlist", e.planner.sequence.shortlist}};
}

/// trial_settings, and for a sweep of generated piles which ones (their names and files say the
/// rest): a folder holds one set of piles.
nlohmann::json sweep_settings(const BenchConfig& config) {
  nlohmann::json settings = trial_settings(config);
  if (config.generated > 0) {
    settings["generated"] = {{"count", config.generated},
                             {"objects", config.pile.objects},
                             {"first_seed", config.pile.seed}};
  }
  return settings;
}

/// A sweep folder's copy of each generated pile's scene file.
constexpr const char* kScenesFolder = "scenes";

/// The files ending in `extension` in a folder's `folder`/ (scenes/ or yardstick/), by file name.
std::map<std::string, fs::path> scene_files(const fs::path& dir, const char* folder = kScenesFolder,
                                            std::string_view extension = ".yaml") {
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

/// The scene a trial runs in: a generated pile's, or what load_scene makes of its source.
sim::Scene trial_scene(const TrialSpec& spec, const BenchConfig& config) {
  for (const sim::PileConfig& pile : bench_piles(config)) {
    if (sim::pile_name(pile) == spec.scene) return sim::pile_scene(pile);
  }
  return sim::load_scene(spec.source);
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
/// from `wanted`.
void require_same_settings(const nlohmann::json& found, const nlohmann::json& wanted,
                           const fs::path& where, std::string_view remedy) {
  for (const auto& [key, value] : wanted.items()) {
    if (!found.contains(key) || found[key] != value) {
      throw std::invalid_argument(
          fmt::format("{}: its trials were run with {} = {}, not {}; {}", where.string(), key,
                      found.contains(key) ? found[key].dump() : "(unset)", value.dump(), remedy));
    }
  }
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

/// The yardstick's truth of each table-top scene of a sweep, computed once (run_bench).
using SurfaceTruths = std::map<std::string, SurfaceTruth>;

std::string run_trial(const TrialSpec& spec, const BenchConfig& config,
                      const SurfaceTruths& truths) {
  const sim::Scene scene = trial_scene(spec, config);
  const ExplorationConfig exploration = trial_config(spec, config, scene);
  Mapper mapper(scene.grid, exploration.mapper);
  const auto found = truths.find(spec.scene);
  const SurfaceTruth* truth = found == truths.end() ? nullptr : &found->second;
  ExplorationResult result;
  if (spec.policy.empty()) {
    result = explore(scene, exploration, mapper, {}, truth);
  } else {
    const auto policy =
        std::find_if(config.policies.begin(), config.policies.end(),
                     [&](const ExternalPolicy& p) { return p.name == spec.policy; });
    // NOTE: a policy's error names the trial it broke; the types stay (bad choice or failure).
    try {
      result = explore_choosing(scene, exploration, mapper, policy->choose, truth);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(fmt::format("trial {}: {}", spec.key(), e.what()));
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(fmt::format("trial {}: {}", spec.key(), e.what()));
    }
  }
  return scans_csv_rows({spec.scene, spec.method, spec.alpha, spec.objective, spec.trial,
                         spec.greedy_oracle, spec.policy},
                        result.scans);
}

}  // namespace

ExplorationConfig trial_config(const TrialSpec& spec, const BenchConfig& config,
                               const sim::Scene& scene) {
  ExplorationConfig exploration = config.exploration;
  exploration.planner.method = spec.method;
  exploration.greedy_oracle = spec.greedy_oracle;
  exploration.planner.gain.alpha = spec.alpha.value;
  exploration.auto_alpha = spec.alpha.automatic;
  exploration.observability.prior = spec.alpha.value;
  if (uses_survival_reading(spec.method) && spec.alpha.automatic) {
    // NOTE: its a is a chance per unobserved cell, with a grid and a prior of its own.
    exploration.observability = survival_fit_config();
    exploration.planner.gain.alpha = exploration.observability.prior;
  }
  exploration.planner.objective = spec.objective;
  exploration.start = spec.trial % static_cast<int>(scene.start_poses.size());
  // NOTE: the seed depends on scene and trial only, so every method of a trial meets the same
  // sensor and pose noise where it takes the same views.
  exploration.seed = config.exploration.seed ^ fnv1a(fmt::format("{}#{}", spec.scene, spec.trial));
  if (config.mapper_from_scene) {
    const MapperConfig given = exploration.mapper;
    exploration.mapper = default_mapper_config(scene);
    exploration.mapper.integration = given.integration;
    exploration.mapper.register_scans = given.register_scans;
    exploration.mapper.segment_table = exploration.mapper.segment_table && given.segment_table;
  }
  return exploration;
}

std::size_t run_bench(const fs::path& dir, const BenchConfig& config,
                      const std::function<void(const TrialEvent&)>& on_trial) {
  config.validate();
  const std::vector<TrialSpec> all = bench_trials(config);  // fails on a bad scene before any work
  fs::create_directories(dir / "trials");
  // NOTE: trial files are resumed by key alone, so a folder must never mix trials run with
  // different settings (12 stops and 20, say) into one scans.csv.
  const nlohmann::json settings = sweep_settings(config);
  if (const nlohmann::json found = read_settings(dir); !found.is_null()) {
    require_same_settings(found, settings, dir / kSettingsFile,
                          "resume with the same settings or choose another --out");
  } else {
    write_atomically(dir / kSettingsFile, settings.dump(2) + "\n");
  }
  // NOTE: written before any trial, so that every trial's scene can be rerun from its file
  // (vantage explore --scene DIR/scenes/NAME.yaml), and checked on resume: a pile this version
  // draws differently must not share a folder with the trials of the old one.
  for (const sim::PileConfig& pile : bench_piles(config)) {
    const std::string text = sim::pile_scene_yaml(sim::generate_pile(pile));
    const fs::path path = dir / kScenesFolder / (sim::pile_name(pile) + ".yaml");
    if (fs::exists(path)) {
      if (read_file(path) != text) {
        throw std::invalid_argument(fmt::format(
            "{}: differs from the pile this version generates for seed {}; its trials were run "
            "in another pile: choose another --out",
            path.string(), pile.seed));
      }
    } else {
      fs::create_directories(path.parent_path());
      write_atomically(path, text);
    }
  }
  const std::map<std::string, fs::path> done = trial_files(dir);

  // NOTE: the yardstick's truth (noise-free scans from every candidate and start) is the scene's
  // and the candidate set's, not a trial's: computed once per table-top scene with a trial to
  // run, and written for scripts/set_cover.py.
  SurfaceTruths truths;
  for (const TrialSpec& spec : all) {
    if (truths.count(spec.scene) > 0) continue;
    const sim::Scene scene = trial_scene(spec, config);
    if (scene.kind != sim::SceneKind::kTableTop) {
      if (spec.greedy_oracle || !spec.policy.empty()) {
        throw std::invalid_argument(
            fmt::format("bench: scene '{}' is an office: {} for table tops", spec.scene,
                        spec.greedy_oracle ? "the greedy oracle is" : "an external policy is"));
      }
      continue;
    }
    const std::vector<Eigen::Isometry3d> candidates = run_candidates(scene, config.exploration);
    check_surface_truth(scene, candidates.size(), config.exploration.budget);
    const sim::World world(scene, sim::WorldConfig{config.exploration.planner.gain.num_threads});
    const SurfaceTruth& truth =
        truths
            .emplace(spec.scene,
                     compute_surface_truth(world, candidates, config.exploration.coverage_tolerance,
                                           config.exploration.planner.gain.num_threads))
            .first->second;
    const fs::path file = dir / kYardstickFolder / (spec.scene + ".json");
    if (!fs::exists(file)) {
      fs::create_directories(file.parent_path());
      write_yardstick_file(file, scene, config.exploration, truth);
    }
  }

  std::vector<TrialSpec> mine;
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (static_cast<int>(k % static_cast<std::size_t>(config.shard_count)) == config.shard_index) {
      mine.push_back(all[k]);
    }
  }

  std::mutex report;
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> finished{0};
  std::atomic<std::size_t> ran{0};
  std::exception_ptr failure;
  auto worker = [&] {
    for (std::size_t k = next++; k < mine.size(); k = next++) {
      const TrialSpec& spec = mine[k];
      TrialEvent event{spec, done.count(spec.key()) > 0, 0.0, 0, mine.size()};
      try {
        if (!event.skipped) {
          const auto start = std::chrono::steady_clock::now();
          const std::string rows = run_trial(spec, config, truths);
          write_atomically(dir / "trials" / (spec.key() + ".csv"), rows);
          event.seconds = seconds_since(start);
          ++ran;
        }
        event.done = ++finished;
        if (on_trial) {
          const std::lock_guard lock(report);
          on_trial(event);
        }
      } catch (...) {
        const std::lock_guard lock(report);
        if (!failure) failure = std::current_exception();
        next = mine.size();  // stop handing out trials; finished ones are kept
      }
    }
  };
  std::vector<std::thread> threads;
  for (int j = 1; j < config.jobs; ++j) threads.emplace_back(worker);
  worker();
  for (std::thread& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);
  write_bench_csv(dir);
  return ran;
}

/// `rows` with every line padded with empty fields to the header's count: a trial file of a
/// sweep from before the last columns were appended.
std::string padded_rows(const std::string& rows) {
  const auto fields =
      static_cast<std::size_t>(std::count(kScansCsvHeader.begin(), kScansCsvHeader.end(), ',')) + 1;
  std::string out;
  std::istringstream lines(rows);
  for (std::string line; std::getline(lines, line);) {
    const auto found = static_cast<std::size_t>(std::count(line.begin(), line.end(), ',')) + 1;
    out += line + std::string(found < fields ? fields - found : 0, ',') + "\n";
  }
  return out;
}

void write_yardstick_file(const fs::path& path, const sim::Scene& scene,
                          const ExplorationConfig& config, const SurfaceTruth& truth) {
  std::map<std::uint32_t, std::size_t> rank;  // cell -> its index in V
  for (std::size_t k = 0; k < truth.visible.size(); ++k) rank[truth.visible[k]] = k;
  auto indices = [&](const std::vector<std::vector<std::uint32_t>>& sets) {
    nlohmann::json out = nlohmann::json::array();
    for (const std::vector<std::uint32_t>& set : sets) {
      std::vector<std::size_t> ids;
      for (const std::uint32_t c : set) ids.push_back(rank.at(c));
      out.push_back(ids);
    }
    return out;
  };
  const std::vector<Eigen::Isometry3d> views = run_candidates(scene, config);
  const TravelRule travel = run_travel_rule(scene, config);
  auto travel_from = [&](const std::vector<Eigen::Isometry3d>& from) {
    nlohmann::json rows = nlohmann::json::array();
    for (const Eigen::Isometry3d& a : from) {
      std::vector<double> row;
      for (const Eigen::Isometry3d& b : views) {
        row.push_back(std::round(travel(a.translation(), b.translation()) * 1e6) / 1e6);
      }
      rows.push_back(row);
    }
    return rows;
  };
  const nlohmann::json file = {
      {"scene", scene.name},
      {"candidates", to_string(config.candidates)},
      {"surface_cells", truth.surface.size()},
      {"visible_cells", truth.visible.size()},
      {"tolerance_cells", truth.tolerance},
      {"rule",
       "views[i] and starts[j]: the visible surface cells (indices into V) that a noise-free scan "
       "from candidate i or start j hits; travel_m: between candidates (views x views) and from "
       "each start to each candidate, under the run's travel rule [m]"},
      {"views", indices(truth.candidate_hits)},
      {"starts", indices(truth.start_hits)},
      {"travel_m",
       {{"views", travel_from(views)}, {"from_starts", travel_from(scene.start_poses)}}}};
  write_atomically(path, file.dump() + "\n");
}

void write_bench_csv(const fs::path& dir) {
  std::string csv = std::string(kScansCsvHeader) + "\n";
  for (const auto& [key, path] : trial_files(dir)) csv += padded_rows(read_file(path));
  write_atomically(dir / "scans.csv", csv);
}

/// Throws std::runtime_error naming `path` unless `rows` are rows of scans.csv: at least one,
/// each with the header's number of fields.
void require_trial_rows(const std::string& rows, const fs::path& path) {
  const auto fields = std::count(kScansCsvHeader.begin(), kScansCsvHeader.end(), ',') + 1;
  std::istringstream lines(rows);
  std::string line;
  std::size_t n = 0;
  while (std::getline(lines, line)) {
    ++n;
    const auto found = std::count(line.begin(), line.end(), ',') + 1;
    // NOTE: a trial file from before the surface columns were appended holds fewer fields.
    if (found != fields && found != static_cast<long>(kScansCsvFieldsBeforeSurface)) {
      throw std::runtime_error(fmt::format(
          "{}: line {} holds {} fields, not the {} of a scans.csv row: not a trial file",
          path.string(), n, found, fields));
    }
  }
  if (n == 0) throw std::runtime_error(fmt::format("{}: empty, not a trial file", path.string()));
}

void merge_bench(const std::vector<fs::path>& dirs, const fs::path& out) {
  if (dirs.empty()) throw std::invalid_argument("bench merge needs at least one folder");
  // NOTE: the target takes part like a source: its settings and its trials must agree with what
  // is merged into it, so nothing of it is replaced unseen.
  std::vector<fs::path> all = dirs;
  std::error_code error;
  const bool target_is_source = std::any_of(dirs.begin(), dirs.end(), [&](const fs::path& dir) {
    return fs::equivalent(dir, out, error);
  });
  if (!target_is_source && fs::exists(out)) all.push_back(out);
  std::map<std::string, std::string> trials;
  std::map<std::string, std::string> scenes;  // generated scene files, by file name
  std::map<std::string, std::string> truths;  // yardstick files, by file name
  nlohmann::json settings = nullptr;          // of the first folder; all must agree
  for (std::size_t k = 0; k < all.size(); ++k) {
    const fs::path& dir = all[k];
    const bool target = k == dirs.size();
    const nlohmann::json found = read_settings(dir);
    if (found.is_null() && !(target && trial_files(dir).empty())) {
      throw std::runtime_error(fmt::format(
          "{}: no {}, so the settings its trials were run with are unknown; only sweeps run with "
          "the same settings can be merged",
          dir.string(), kSettingsFile));
    }
    if (settings.is_null()) {
      settings = found;
    } else if (!found.is_null()) {
      // NOTE: both ways, so a setting one folder has and the other lacks is a difference too.
      const std::string remedy = "only sweeps run with the same settings can be merged";
      require_same_settings(found, settings, dir / kSettingsFile, remedy);
      require_same_settings(settings, found, all.front() / kSettingsFile, remedy);
    }
    for (const auto& [name, path] : scene_files(dir)) {
      const auto [it, inserted] = scenes.emplace(name, read_file(path));
      if (!inserted && it->second != read_file(path)) {
        throw std::runtime_error(fmt::format(
            "{}: differs from the scene file of the same name in another folder", path.string()));
      }
    }
    for (const auto& [name, path] : scene_files(dir, kYardstickFolder, ".json")) {
      const auto [it, inserted] = truths.emplace(name, read_file(path));
      if (!inserted && it->second != read_file(path)) {
        throw std::runtime_error(
            fmt::format("{}: differs from the yardstick file of the same name in another folder",
                        path.string()));
      }
    }
    const auto files = trial_files(dir);
    if (files.empty() && !target) {
      throw std::runtime_error(fmt::format("{}: no trials/ with trial files", dir.string()));
    }
    for (const auto& [key, path] : files) {
      const std::string rows = read_file(path);
      require_trial_rows(rows, path);
      const auto [it, inserted] = trials.emplace(key, rows);
      if (!inserted && it->second != rows) {
        throw std::runtime_error(fmt::format(
            "{}: trial {} differs from the same trial in another folder{}", path.string(), key,
            target ? " (the --out folder's would be replaced)" : ""));
      }
    }
  }
  fs::create_directories(out / "trials");
  if (!settings.is_null() && read_settings(out).is_null()) {
    write_atomically(out / kSettingsFile, settings.dump(2) + "\n");
  }
  for (const auto& [key, rows] : trials) write_atomically(out / "trials" / (key + ".csv"), rows);
  if (!scenes.empty()) fs::create_directories(out / kScenesFolder);
  for (const auto& [name, text] : scenes) write_atomically(out / kScenesFolder / name, text);
  if (!truths.empty()) fs::create_directories(out / kYardstickFolder);
  for (const auto& [name, text] : truths) write_atomically(out / kYardstickFolder / name, text);
  write_bench_csv(out);
}

}  // namespace vantage
