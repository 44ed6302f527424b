#pragma once
/// @file
/// The paper's experiments as a sweep: scenes x methods x trials, each trial an exploration from
/// its own start. Trials run in parallel, can be split into shards for a cluster, and are written
/// one file each, atomically, so an interrupted sweep resumes where it stopped.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "vantage/experiment/exploration.hpp"
#include "vantage/gain/ray_model.hpp"
#include "vantage/sim/generate.hpp"
#include "vantage/sim/object_scene.hpp"

namespace vantage {

/// One trial of a sweep.
struct TrialSpec {
  std::string scene;  ///< the scene's name
  /// What to load it from: a built-in name or a YAML path; for a generated pile the command that
  /// writes its scene file (sim::pile_command).
  std::string source;
  PlannerMethod method = PlannerMethod::kProbabilistic;
  AlphaSetting alpha;                              ///< the probabilistic method's a
  GainObjective objective = GainObjective::kBits;  ///< what the probabilistic method ranks by
  int trial = 0;  ///< starts from the scene's start pose `trial` (mod the number of starts)
  /// The greedy oracle (ExplorationConfig::greedy_oracle) rather than `method` (greedy's
  /// settings stand in for it).
  bool greedy_oracle = false;
  /// An external policy's name (BenchConfig::policies): it chooses the views, not `method`
  /// (greedy's settings stand in for it).
  std::string policy = {};

  /// File-name key, e.g. "tabletop-1__probabilistic__a0.997__t3", "..._aauto__cells__t3".
  std::string key() const;
};

/// A planner outside the library (Python's vt.bench_policy): its trials run the methods' loop,
/// from the same starts with the same seeds, on table tops, and it chooses each view after the
/// start's (explore_choosing).
struct ExternalPolicy {
  /// Its scans.csv method and trial keys: letters, digits, '_', '.', '-', and no built-in
  /// method's name.
  std::string name;
  ViewChooser choose;
};

/// Settings of a sweep.
struct BenchConfig {
  std::vector<std::string> scenes = {"tabletop-1", "tabletop-2", "tabletop-3", "tabletop-4"};
  /// Generated piles benched after `scenes` (docs/scenes.md, "Generated piles"): this many, of
  /// `pile.objects` objects each, with seeds pile.seed, pile.seed + 1, ...; 0: none. Each one's
  /// scene file is written to `DIR/scenes/NAME.yaml`.
  int generated = 0;
  sim::PileConfig pile;  ///< the first generated pile's settings; the others differ in seed
  /// How a scene named by a mesh file or a built-in model is placed: a single object on its view
  /// sphere (sim/object_scene.hpp; `vantage bench objects`).
  sim::ObjectProtocol objects;
  std::vector<PlannerMethod> methods = {PlannerMethod::kProbabilistic, PlannerMethod::kGreedy,
                                        PlannerMethod::kRandom};
  /// a settings for the probabilistic and survival methods (a value, or auto); one trial set
  /// each. Empty: each method's own, as explore runs it (default_alpha_setting with paper_alpha).
  std::vector<AlphaSetting> alphas = {AlphaSetting{false, kTableTopAlpha}};
  /// What they rank by; one trial set per alpha and objective. Empty: each method's own
  /// (natural_objective: cells for survival, bits for probabilistic).
  std::vector<GainObjective> objectives = {GainObjective::kBits};
  /// Also run the greedy oracle (table tops; ExplorationConfig::greedy_oracle), one trial set per
  /// scene after the methods'. `methods` may then be empty.
  bool greedy_oracle = false;
  /// External policies, one trial set per scene each after everything else's (so the others'
  /// trial order, and their shards, stay as without them). `methods` may then be empty.
  std::vector<ExternalPolicy> policies;
  double paper_alpha = kTableTopAlpha;  ///< the paper's a for the sweep's kind (§5.1, §5.2)
  int trials = 10;
  ExplorationConfig exploration;  ///< method, alpha, start and seed are set per trial
  bool mapper_from_scene = true;  ///< table segmentation where the scene has a table
  int jobs = 1;                   ///< trials run at once
  int shard_index = 0;            ///< this process runs trials k with k % shard_count == index
  int shard_count = 1;

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// The paper's office sweep (§5.2, Figs. 15 and 16): both offices at both clutter levels, all
/// five methods (the probabilistic one with a = kOfficeAlpha and 0.999), trial i from start pose i
/// of 5, 20 stops each.
BenchConfig office_bench_config();

/// The generated piles of a sweep, in order: config.pile with seeds pile.seed + k, k < generated.
std::vector<sim::PileConfig> bench_piles(const BenchConfig& config);

/// Every trial of the sweep in its fixed order, before sharding: the named scenes', then the
/// generated piles'. Loads each scene once, to name
/// it; throws what load_scene throws.
std::vector<TrialSpec> bench_trials(const BenchConfig& config);

/// The exploration settings of one trial in `scene`: config.exploration with the trial's method,
/// a and objective, its start (trial mod the scene's starts), its seed (the sweep's seed mixed
/// with the scene's name and the trial, the same for every method) and the scene's mapper.
ExplorationConfig trial_config(const TrialSpec& spec, const BenchConfig& config,
                               const sim::Scene& scene);

/// How a trial went, for progress output.
struct TrialEvent {
  TrialSpec spec;
  bool skipped = false;  ///< already done by an earlier run
  double seconds = 0.0;
  std::size_t done = 0;   ///< trials of this shard finished so far, skipped ones included
  std::size_t total = 0;  ///< trials of this shard
};

/// The folder of a sweep that holds, per table-top scene, `SCENE.json`: the yardstick's truth
/// for the sweep's candidate set (write_yardstick_file), which scripts/set_cover.py reads.
inline constexpr const char* kYardstickFolder = "yardstick";

/// Writes the yardstick's truth of a table-top scene for scripts/set_cover.py, atomically: the
/// sizes of S and V, each candidate's and start's hit set as indices into V (ascending), and the
/// travel between views and from each start to each view under the run's travel rule [m].
void write_yardstick_file(const std::filesystem::path& path, const sim::Scene& scene,
                          const ExplorationConfig& config, const SurfaceTruth& truth);

/// Runs this shard's trials that `dir/trials/` does not hold yet, then writes `dir/scans.csv`
/// from all trial files present. The generated piles' scene files go to `dir/scenes/` first; one
/// that is there already and differs (another version's generator) throws std::invalid_argument.
/// Returns the number of trials run now. What shapes a trial's rows besides its key is kept in
/// `dir/sweep.json`: the settings (stops, seed, evaluation, mapping, ...), the binary's version
/// and git commit (build_info.hpp) and each scene's content hash (its file's text and the solids
/// it loads to); resuming a folder with other settings, another binary, or a scene of its name
/// with other content throws std::invalid_argument naming the first that differs (a resumed sweep
/// may add scenes). `on_trial` is called from the worker threads, one call at a time.
std::size_t run_bench(const std::filesystem::path& dir, const BenchConfig& config,
                      const std::function<void(const TrialEvent&)>& on_trial = {});

/// Joins the trial files of several sweep folders (e.g. shards) into `out/trials/`, their
/// generated scene files into `out/scenes/` and their yardstick files into `out/yardstick/`, and
/// writes `out/scans.csv` and `out/sweep.json` (the scenes' hashes of all). Throws
/// std::runtime_error when two folders hold the same trial with different contents, and
/// std::invalid_argument, in one line naming the field and both folders, when their sweep.json
/// differ in a setting, the binary's version or commit, or the content of a scene both hold.
void merge_bench(const std::vector<std::filesystem::path>& dirs, const std::filesystem::path& out);

/// Writes `dir/scans.csv`: the header and every trial file's rows, in key order.
void write_bench_csv(const std::filesystem::path& dir);

}  // namespace vantage
