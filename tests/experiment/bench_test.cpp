// The sweep resumes after an interruption and gives the same final CSV as an uninterrupted run;
// shards merge into the same CSV too.

#include "vantage/experiment/bench.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "test_scene.hpp"
#include "vantage/experiment/build_info.hpp"
#include "vantage/sim/generate.hpp"

namespace vantage {
namespace {

BenchConfig tiny_sweep() {
  BenchConfig config;
  config.scenes = {testing::small_scene_path()};
  config.methods = {PlannerMethod::kProbabilistic, PlannerMethod::kRandom};
  config.trials = 2;
  config.exploration.scans = 2;
  config.exploration.mapper.register_scans = false;  // resuming is what is tested here
  config.jobs = 2;
  return config;
}

struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("killed") {}
};

TEST(Bench, ResumesAfterAnInterruptionWithTheSameResult) {
  const BenchConfig config = tiny_sweep();
  const auto whole = testing::fresh_dir("bench-whole");
  EXPECT_EQ(run_bench(whole, config), 4u);

  const auto resumed = testing::fresh_dir("bench-resumed");
  BenchConfig serial = config;
  serial.jobs = 1;
  EXPECT_THROW(run_bench(resumed, serial, [](const TrialEvent&) { throw Interrupted(); }),
               Interrupted);
  EXPECT_EQ(run_bench(resumed, config), 3u);  // the first trial was kept
  EXPECT_EQ(run_bench(resumed, config), 0u);  // nothing left to do
  EXPECT_EQ(testing::without_timing(testing::read_text(resumed / "scans.csv")),
            testing::without_timing(testing::read_text(whole / "scans.csv")));

  // Two shards, merged, hold the same rows.
  const auto a = testing::fresh_dir("bench-shard-a");
  const auto b = testing::fresh_dir("bench-shard-b");
  BenchConfig shard = config;
  shard.shard_count = 2;
  shard.shard_index = 0;
  run_bench(a, shard);
  shard.shard_index = 1;
  run_bench(b, shard);
  const auto merged = testing::fresh_dir("bench-merged");
  merge_bench({a, b}, merged);
  EXPECT_EQ(testing::without_timing(testing::read_text(merged / "scans.csv")),
            testing::without_timing(testing::read_text(whole / "scans.csv")));
  EXPECT_EQ(testing::parse_csv(testing::read_text(merged / "scans.csv")).size(), 1u + 4u * 2u);
}

// A folder never mixes trials run with different settings: resuming it with other ones fails
// before any trial runs, naming the setting, and leaves its files as they were.
TEST(Bench, RefusesToResumeAFolderWithOtherSettings) {
  BenchConfig config = tiny_sweep();
  config.scenes.resize(1);
  config.methods = {PlannerMethod::kRandom};
  config.trials = 1;
  const auto dir = testing::fresh_dir("bench-settings");
  ASSERT_EQ(run_bench(dir, config), 1u);
  const std::string rows = testing::read_text(dir / "scans.csv");

  BenchConfig longer = config;
  longer.exploration.scans += 1;
  try {
    run_bench(dir, longer);
    FAIL() << "resumed a folder run with another number of scans";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("scans"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("sweep.json"), std::string::npos) << e.what();
  }
  EXPECT_EQ(testing::read_text(dir / "scans.csv"), rows);
  // A sequence's sample rate, the search and the hemisphere's radii change a trial's rows too.
  BenchConfig sparser = config;
  sparser.exploration.planner.sequence.sample_bits += 2;
  EXPECT_THROW(run_bench(dir, sparser), std::invalid_argument);
  BenchConfig searched = config;
  searched.exploration.planner.search = DecisionSearch::kExhaustive;
  EXPECT_THROW(run_bench(dir, searched), std::invalid_argument);
  BenchConfig wider = config;
  wider.exploration.hemisphere.radii = {1.2};
  EXPECT_THROW(run_bench(dir, wider), std::invalid_argument);
  EXPECT_EQ(run_bench(dir, config), 0u);  // the same settings resume as before

  const auto other = testing::fresh_dir("bench-settings-other");
  longer.exploration.seed += 1;
  longer.exploration.scans = config.exploration.scans;
  run_bench(other, longer);
  EXPECT_THROW(merge_bench({dir, other}, testing::fresh_dir("bench-settings-merged")),
               std::invalid_argument);
}

// issue 27: merge never mixes, overwrites or replaces unseen, and takes only trial files.
TEST(Bench, MergeRefusesWhatWouldMixOrReplace) {
  BenchConfig config = tiny_sweep();
  config.methods = {PlannerMethod::kRandom};
  config.trials = 1;
  config.jobs = 1;
  const auto a = testing::fresh_dir("bench-merge-a");
  run_bench(a, config);
  const auto key = bench_trials(config).front().key();
  const auto merged = testing::fresh_dir("bench-merge-out");
  merge_bench({a}, merged);
  const std::string settings = testing::read_text(merged / "sweep.json");

  // A target of another sweep's settings: refused, its sweep.json kept.
  BenchConfig other = config;
  other.exploration.seed += 1;
  const auto b = testing::fresh_dir("bench-merge-b");
  run_bench(b, other);
  EXPECT_THROW(merge_bench({b}, merged), std::invalid_argument);
  EXPECT_EQ(testing::read_text(merged / "sweep.json"), settings);

  // A trial of the same name with other rows in the target: refused, not replaced.
  const auto c = testing::fresh_dir("bench-merge-c");
  std::filesystem::copy(
      a, c,
      std::filesystem::copy_options::recursive | std::filesystem::copy_options::overwrite_existing);
  std::string rows = testing::read_text(c / "trials" / (key + ".csv"));
  rows.replace(rows.find(",1,"), 3, ",7,");  // another trial number: other rows, same key
  testing::write_text(c / "trials" / (key + ".csv"), rows);
  EXPECT_THROW(merge_bench({c}, merged), std::runtime_error);

  // A folder without settings, and a trial file that is no trial: refused, naming the file.
  const auto d = testing::fresh_dir("bench-merge-d");
  std::filesystem::create_directories(d / "trials");
  testing::write_text(d / "trials" / "x.csv", "this,is\nnot a trial\n");
  EXPECT_THROW(merge_bench({a, d}, testing::fresh_dir("bench-merge-e")), std::runtime_error);
  testing::write_text(d / "sweep.json", "{not json");
  try {
    merge_bench({a, d}, testing::fresh_dir("bench-merge-g"));
    FAIL() << "merged a folder whose sweep.json is not JSON";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("sweep.json: not a sweep settings file: not valid JSON"),
              std::string::npos)
        << e.what();
    EXPECT_EQ(std::string(e.what()).find("json.exception"), std::string::npos) << e.what();
  }
  testing::write_text(d / "sweep.json", settings);
  try {
    merge_bench({a, d}, testing::fresh_dir("bench-merge-f"));
    FAIL() << "merged a trial file that is not one";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("x.csv: line 1 holds 2 fields"), std::string::npos)
        << e.what();
  }
}

// issue 27: a sweep without --alphas and --objectives runs each method as explore does (one
// source of the defaults): the survival reading fitted online ranking by cells, the paper's
// method at the paper's a ranking by bits.
TEST(Bench, EachMethodRunsItsOwnDefaultsWhenNoneAreGiven) {
  BenchConfig config = tiny_sweep();
  config.methods = {PlannerMethod::kSurvival, PlannerMethod::kProbabilistic,
                    PlannerMethod::kGreedy};
  config.trials = 1;
  config.alphas.clear();
  config.objectives.clear();
  config.validate();
  const std::vector<TrialSpec> trials = bench_trials(config);
  ASSERT_EQ(trials.size(), 3u);
  EXPECT_EQ(trials[0].method, PlannerMethod::kSurvival);
  EXPECT_EQ(trials[0].alpha, default_alpha_setting(PlannerMethod::kSurvival, kTableTopAlpha));
  EXPECT_TRUE(trials[0].alpha.automatic);
  EXPECT_EQ(trials[0].alpha.value, kSurvivalAlpha);
  EXPECT_EQ(trials[0].objective, GainObjective::kCells);
  EXPECT_EQ(trials[1].alpha, (AlphaSetting{false, kTableTopAlpha}));
  EXPECT_EQ(trials[1].objective, GainObjective::kBits);
  EXPECT_NE(trials[0].key().find("__survival__aauto__cells__t0"), std::string::npos)
      << trials[0].key();
}

// issue 26: --generated N expands into N piles named by objects and seed, so their trial keys
// stay the same whatever N is (a resumed or merged sweep finds them), each source the command
// that writes the pile, each scene file in the folder, and a changed one is refused on resume.
TEST(Bench, GeneratedPilesHaveStableKeysAndTheirSceneFiles) {
  BenchConfig config = tiny_sweep();
  config.scenes.clear();
  config.methods = {PlannerMethod::kRandom};
  config.trials = 1;
  config.exploration.scans = 1;
  config.generated = 2;
  config.pile.objects = 4;
  config.pile.seed = 5;
  config.validate();
  const std::vector<TrialSpec> trials = bench_trials(config);
  ASSERT_EQ(trials.size(), 2u);
  EXPECT_EQ(trials[0].key(), "pile-4-s0005__random__t0");
  EXPECT_EQ(trials[1].key(), "pile-4-s0006__random__t0");
  EXPECT_EQ(trials[1].source, "vantage scene generate --objects 4 --seed 6");
  BenchConfig more = config;
  more.generated = 3;
  EXPECT_EQ(bench_trials(more)[1].key(), trials[1].key());
  BenchConfig none = config;
  none.generated = 0;
  EXPECT_THROW(none.validate(), std::invalid_argument);  // no scenes at all

  const auto dir = testing::fresh_dir("bench-generated");
  ASSERT_EQ(run_bench(dir, config), 2u);
  const auto scene_file = dir / "scenes" / "pile-4-s0006.yaml";
  sim::PileConfig pile = config.pile;
  pile.seed = 6;
  EXPECT_EQ(testing::read_text(scene_file), sim::pile_scene_yaml(sim::generate_pile(pile)));
  EXPECT_EQ(sim::load_scene(scene_file.string()).name, "pile-4-s0006");
  EXPECT_NE(testing::read_text(dir / "sweep.json").find("\"generated\""), std::string::npos);
  EXPECT_EQ(testing::parse_csv(testing::read_text(dir / "scans.csv")).size(), 1u + 2u);

  const auto merged = testing::fresh_dir("bench-generated-merged");
  merge_bench({dir}, merged);
  EXPECT_EQ(testing::read_text(merged / "scenes" / "pile-4-s0006.yaml"),
            testing::read_text(scene_file));

  testing::write_text(scene_file, testing::read_text(scene_file) + "# edited\n");
  EXPECT_THROW(run_bench(dir, config), std::invalid_argument);
}

/// `dir`'s sweep.json with `field` set to `value` (a JSON text).
void set_setting(const std::filesystem::path& dir, const std::string& field,
                 const std::string& value) {
  std::string text = testing::read_text(dir / "sweep.json");
  const std::string key = "\"" + field + "\": ";
  const std::size_t at = text.find(key);
  ASSERT_NE(at, std::string::npos) << field;
  const std::size_t from = at + key.size();
  text.replace(from, text.find_first_of(",\n", from) - from, value);
  testing::write_text(dir / "sweep.json", text);
}

/// A copy of folder `from` as `to`.
void copy_folder(const std::filesystem::path& from, const std::filesystem::path& to) {
  std::filesystem::copy(
      from, to,
      std::filesystem::copy_options::recursive | std::filesystem::copy_options::overwrite_existing);
}

// issue 50: sweep.json records what makes a row reproducible (the binary's version and commit,
// the settings, the seed, each scene's content hash), and a folder of another binary or another
// scene of the same name is neither resumed nor merged: one line names the field and both folders.
TEST(Bench, SweepRecordsTheBinaryAndTheScenesAndMergeRefusesOthers) {
  BenchConfig config = tiny_sweep();
  config.methods = {PlannerMethod::kRandom};
  config.trials = 1;
  config.jobs = 1;
  const auto a = testing::fresh_dir("bench-provenance-a");
  run_bench(a, config);
  const std::string settings = testing::read_text(a / "sweep.json");
  EXPECT_NE(settings.find("\"commit\": \"" + std::string(build_commit()) + "\""), std::string::npos)
      << settings;
  EXPECT_NE(settings.find("\"version\": \"" + std::string(build_version()) + "\""),
            std::string::npos)
      << settings;
  EXPECT_NE(settings.find("\"seed\": 1"), std::string::npos) << settings;
  EXPECT_NE(settings.find("\"small-tabletop\": \"fnv1a64:"), std::string::npos) << settings;
  EXPECT_FALSE(build_commit().empty());

  // Another commit: merge names the field and both folders; resuming is refused too.
  const auto b = testing::fresh_dir("bench-provenance-b");
  copy_folder(a, b);
  set_setting(b, "commit", "\"0123456789abcdef0123456789abcdef01234567\"");
  try {
    merge_bench({a, b}, testing::fresh_dir("bench-provenance-merged"));
    FAIL() << "merged folders of two commits";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("commit differs"), std::string::npos) << message;
    EXPECT_NE(message.find((a / "sweep.json").string()), std::string::npos) << message;
    EXPECT_NE(message.find((b / "sweep.json").string()), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_THROW(run_bench(b, config), std::invalid_argument);

  // A scene of the same name with other content (an edited scene file): refused the same ways.
  const auto c = testing::fresh_dir("bench-provenance-c");
  copy_folder(a, c);
  set_setting(c, "small-tabletop", "\"fnv1a64:0000000000000000\"");
  try {
    merge_bench({a, c}, testing::fresh_dir("bench-provenance-merged-c"));
    FAIL() << "merged folders of two scenes of one name";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the content of scene 'small-tabletop' differs"),
              std::string::npos)
        << e.what();
  }
  const auto edited = testing::fresh_dir("bench-provenance-scene") / "small_tabletop.yaml";
  testing::write_text(edited,
                      testing::read_text(testing::small_scene_path()) + "# another scene\n");
  BenchConfig other = config;
  other.scenes = {edited.string()};
  try {
    run_bench(a, other);
    FAIL() << "resumed a folder in another scene of the same name";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("another scene 'small-tabletop'"), std::string::npos)
        << e.what();
  }

  // A folder from before sweep.json held the binary: said as such, not resumed.
  const auto d = testing::fresh_dir("bench-provenance-d");
  copy_folder(a, d);
  std::string old = testing::read_text(d / "sweep.json");
  old.erase(old.find("  \"commit\""),
            old.find('\n', old.find("  \"commit\"")) + 1 - old.find("  \"commit\""));
  testing::write_text(d / "sweep.json", old);
  try {
    run_bench(d, config);
    FAIL() << "resumed a folder without the binary's record";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("written before sweep.json recorded the binary"),
              std::string::npos)
        << e.what();
  }

  // Folders of other scenes merge: the merged sweep.json holds both scenes' hashes.
  BenchConfig more = config;
  more.scenes = {"tabletop-1"};
  more.exploration.scans = config.exploration.scans;
  const auto e = testing::fresh_dir("bench-provenance-e");
  run_bench(e, more);
  const auto merged = testing::fresh_dir("bench-provenance-merged-e");
  merge_bench({a, e}, merged);
  const std::string both = testing::read_text(merged / "sweep.json");
  EXPECT_NE(both.find("\"small-tabletop\": \"fnv1a64:"), std::string::npos) << both;
  EXPECT_NE(both.find("\"tabletop-1\": \"fnv1a64:"), std::string::npos) << both;
}

TEST(Bench, RejectsBadShardsAndUnknownScenes) {
  BenchConfig config = tiny_sweep();
  config.shard_count = 2;
  config.shard_index = 2;
  EXPECT_THROW(config.validate(), std::invalid_argument);
  config = tiny_sweep();
  config.scenes = {"no-such-scene"};
  EXPECT_THROW(run_bench(testing::fresh_dir("bench-bad"), config), std::runtime_error);
}

}  // namespace
}  // namespace vantage
