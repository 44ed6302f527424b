// The sweep resumes after an interruption and gives the same final CSV as an uninterrupted run;
// shards merge into the same CSV too.

#include "vantage/experiment/bench.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "test_scene.hpp"

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
  EXPECT_EQ(run_bench(dir, config), 0u);  // the same settings resume as before

  const auto other = testing::fresh_dir("bench-settings-other");
  longer.exploration.seed += 1;
  longer.exploration.scans = config.exploration.scans;
  run_bench(other, longer);
  EXPECT_THROW(merge_bench({dir, other}, testing::fresh_dir("bench-settings-merged")),
               std::invalid_argument);
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
