#include "vantage/experiment/bench.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <atomic>
#include <bit>
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

#include "vantage/experiment/build_info.hpp"
#include "vantage/experiment/decision_cost.hpp"
#include "vantage/experiment/detail/sweep_files.hpp"
#include "vantage/experiment/results.hpp"
#include "vantage/experiment/yardstick.hpp"
#include "vantage/io/atomic_file.hpp"
#include "vantage/sim/scene.hpp"
#include "vantage/util/clock.hpp"

namespace vantage {
namespace fs = std::filesystem;
using namespace detail;  // the sweep folder's files (detail/sweep_files.hpp)
namespace {

/// The scene a trial runs in: a generated pile's, or what load_scene makes of its source.
sim::Scene trial_scene(const TrialSpec& spec, const BenchConfig& config) {
  for (const sim::PileConfig& pile : bench_piles(config)) {
    if (sim::pile_name(pile) == spec.scene) return sim::pile_scene(pile);
  }
  return sim::load_scene(spec.source, config.objects);
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

// NOTE: trial files are resumed by key alone, so a folder must never mix trials run with
// different settings (12 stops and 20, say) into one scans.csv.
// The binary and the scenes' content too: a folder's rows are one binary's in one set of
// scenes, so others can check them. A resumed sweep may add scenes.
void check_settings(const fs::path& dir, const BenchConfig& config) {
  nlohmann::json settings = sweep_settings(config);
  settings[kScenesKey] = scene_hashes(config);
  if (const nlohmann::json found = read_settings(dir); !found.is_null()) {
    const std::string remedy = "resume with the same settings and binary or choose another --out";
    require_same_settings(found, settings, dir / kSettingsFile, remedy);
    require_same_scenes(found, settings[kScenesKey], dir / kSettingsFile, remedy);
    if (const nlohmann::json more = with_scenes(found, settings); more != found) {
      write_atomically(dir / kSettingsFile, more.dump(2) + "\n");
    }
  } else {
    write_atomically(dir / kSettingsFile, settings.dump(2) + "\n");
  }
}

// NOTE: written before any trial, so that every trial's scene can be rerun from its file
// (vantage explore --scene DIR/scenes/NAME.yaml), and checked on resume: a pile this version
// draws differently must not share a folder with the trials of the old one.
void write_piles(const fs::path& dir, const BenchConfig& config) {
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
}

// NOTE: the yardstick's truth (noise-free scans from every candidate and start) is the scene's
// and the candidate set's, not a trial's: computed once per table-top scene with a trial to
// run, and written for scripts/set_cover.py.
SurfaceTruths surface_truths(const fs::path& dir, const std::vector<TrialSpec>& all,
                             const BenchConfig& config) {
  SurfaceTruths truths;
  for (const TrialSpec& spec : all) {
    if (truths.count(spec.scene) > 0) continue;
    const sim::Scene scene = trial_scene(spec, config);
    if (scene.kind == sim::SceneKind::kOffice) {
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
  return truths;
}

/// Runs the trials `mine` not `done` on config.jobs threads, each into its trial file, and
/// reports every trial to `on_trial`; the first failure stops the handing out and is rethrown.
/// Returns how many ran.
std::size_t run_trials(const fs::path& dir, const std::vector<TrialSpec>& mine,
                       const std::map<std::string, fs::path>& done, const BenchConfig& config,
                       const SurfaceTruths& truths,
                       const std::function<void(const TrialEvent&)>& on_trial) {
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
  return ran;
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
  check_settings(dir, config);
  write_piles(dir, config);
  const std::map<std::string, fs::path> done = trial_files(dir);
  const SurfaceTruths truths = surface_truths(dir, all, config);
  std::vector<TrialSpec> mine;
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (static_cast<int>(k % static_cast<std::size_t>(config.shard_count)) == config.shard_index) {
      mine.push_back(all[k]);
    }
  }
  const std::size_t ran = run_trials(dir, mine, done, config, truths, on_trial);
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
  const PlacedViews placed = run_candidate_views(scene, config);
  const std::vector<Eigen::Isometry3d>& views = placed.poses;
  const TravelRule& travel = placed.travel;
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
      {"candidates", run_candidate_set(scene, config)},
      {"surface_cells", truth.surface.size()},
      {"visible_cells", truth.visible.size()},
      {"tolerance_cells", truth.tolerance.cells},
      {"tolerance_m", truth.tolerance.metres},
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

}  // namespace vantage
