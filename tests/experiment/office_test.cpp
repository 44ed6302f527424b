// A short office exploration end to end (two stops on a small office): the same invariants as
// the table-top run, what an office adds (travel, fallback, path), determinism, and the sweep's
// planning frusta.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <random>

#include "test_scene.hpp"
#include "vantage/experiment/bench.hpp"
#include "vantage/experiment/exploration.hpp"
#include "vantage/experiment/results.hpp"
#include "vantage/io/octomap_io.hpp"

namespace vantage {
namespace {

using testing::parse_csv;
using testing::read_text;

std::string office_path() {
  return (testing::source_dir() / "tests/experiment/small_office.yaml").string();
}

struct OfficeRun {
  ExplorationResult result;
  std::string csv;
};

OfficeRun office_run(PlannerMethod method, int threads, int stops = 2,
                     const std::filesystem::path* dir = nullptr) {
  const sim::Scene scene = sim::load_scene(office_path());
  ExplorationConfig config;
  config.scans = stops;
  config.seed = 11;
  config.planner.method = method;
  config.planner.gain.alpha = 0.9999;
  config.planner.gain.num_threads = threads;
  config.planner.greedy_reference = true;  // TwoStopsMeetTheTableTopInvariants compares it
  config.mapper = default_mapper_config(scene);
  config.mapper.integration.num_threads = threads;
  Mapper mapper(scene.grid, config.mapper);
  OfficeRun run;
  run.result = explore(scene, config, mapper);
  run.csv = std::string(kScansCsvHeader) + "\n" +
            scans_csv_rows(run_label(scene.name, config), run.result.scans);
  if (dir != nullptr) write_run_files(*dir, scene, config, run.result, mapper);
  return run;
}

TEST(Office, TwoStopsMeetTheTableTopInvariants) {
  const std::filesystem::path dir = testing::fresh_dir("office");
  const OfficeRun run = office_run(PlannerMethod::kProbabilistic, 0, 2, &dir);
  const auto& scans = run.result.scans;
  ASSERT_EQ(scans.size(), 2u) << run.result.stop_reason;
  EXPECT_FALSE(scans[0].predicted_gain.has_value());
  ASSERT_TRUE(scans[1].predicted_gain.has_value());
  EXPECT_GT(*scans[1].predicted_gain, 0.0);
  ASSERT_TRUE(scans[1].greedy_predicted_gain.has_value());
  EXPECT_GE(*scans[1].greedy_predicted_gain, *scans[1].predicted_gain);  // a < 1 sees less
  EXPECT_GT(run.result.observable_cells, 0u);

  std::size_t previous = 80u * 40u * 20u;
  for (const ScanRecord& r : scans) {
    EXPECT_LE(r.unobserved, previous) << "stop " << r.scan;  // never increases
    EXPECT_EQ(r.actual_gain, previous - r.unobserved + r.reentered) << "stop " << r.scan;
    EXPECT_GE(r.actual_gain, previous - r.unobserved);
    EXPECT_GT(r.points, r.object_points);  // thinned to one point per cell
    EXPECT_LE(r.pose_error_after, r.pose_error_before + 1e-3) << "stop " << r.scan;
    EXPECT_LE(r.displacement_after, r.displacement_before + 1e-3) << "stop " << r.scan;
    EXPECT_GT(r.object_points, 0u);
    EXPECT_GE(r.coverage, 0.0);
    EXPECT_LE(r.coverage, 1.0);
    previous = r.unobserved;
  }
  EXPECT_GT(scans[1].coverage, scans[0].coverage);

  // The second stop: reached by driving on the floor, at least min_move from the first.
  EXPECT_EQ(scans[0].travel, 0.0);
  EXPECT_GT(scans[1].travel, 0.0);
  ASSERT_GE(scans[1].path.size(), 2u);
  EXPECT_TRUE(scans[1].path.front().head<2>().isApprox(
      scans[0].T_world_sensor.translation().head<2>(), 0.1));
  EXPECT_LE(
      (scans[1].path.back().head<2>() - scans[1].T_world_sensor.translation().head<2>()).norm(),
      0.1 * std::sqrt(0.5) + 1e-9);                 // the stop lies in the path's last cell
  for (const Eigen::Vector3d& p : scans[1].path) {  // the sensor's path, at its height
    EXPECT_NEAR(p.z(), scans[1].T_world_sensor.translation().z(), 1e-9);
  }
  EXPECT_GE((scans[1].T_world_sensor.translation() - scans[0].T_world_sensor.translation())
                .head<2>()
                .norm(),
            OfficeConfig{}.min_move - 0.1);
  ASSERT_TRUE(scans[1].goal.has_value());
  if (!scans[1].fallback) {
    EXPECT_TRUE(
        scans[1].goal->head<2>().isApprox(scans[1].T_world_sensor.translation().head<2>(), 1e-9));
  }
  EXPECT_NEAR(scans[1].T_world_sensor.translation().z(), 1.0, 1e-12);  // the sensor's mount
  EXPECT_GT(scans[1].candidates, 0);
  EXPECT_GT(scans[1].pose_error_before, 0.0);  // the second stop was believed with noise

  // The files parse and say the same.
  const std::string csv = read_text(dir / "scans.csv");
  EXPECT_EQ(csv.substr(0, kScansCsvHeader.size()), kScansCsvHeader);
  const auto rows = parse_csv(csv);
  ASSERT_EQ(rows.size(), 3u);
  ASSERT_EQ(rows[0].size(), 29u);
  // An office has no fixed candidate set, so no surface coverage (docs/yardstick.md).
  EXPECT_EQ(rows[0][27], "surface_coverage");
  EXPECT_EQ(rows[2][27], "");
  EXPECT_EQ(rows[2][28], "");
  EXPECT_EQ(rows[0][12], "travel_m");
  EXPECT_EQ(rows[0][13], "fallback");
  EXPECT_EQ(rows[0][14], "predicted_cells");
  EXPECT_EQ(rows[1][14], "");  // no prediction before the first stop
  ASSERT_TRUE(scans[1].predicted_cells.has_value());
  EXPECT_NEAR(std::stod(rows[2][14]), *scans[1].predicted_cells, 1e-9 * *scans[1].predicted_cells);
  EXPECT_GT(*scans[1].predicted_cells, 0.0);
  EXPECT_EQ(rows[1][12], "0");
  EXPECT_DOUBLE_EQ(std::stod(rows[2][12]), scans[1].travel);
  EXPECT_EQ(rows[2][13], scans[1].fallback ? "1" : "0");
  EXPECT_EQ(rows[2][8], std::to_string(scans[1].actual_gain));
  EXPECT_EQ(rows[0][19], "pose_error_final_m");
  EXPECT_NEAR(std::stod(rows[2][19]), scans[1].pose_error_final, 1e-6 * scans[1].pose_error_final);
  const auto json = nlohmann::json::parse(read_text(dir / "run.json"));
  EXPECT_EQ(json["scene"]["kind"], "office");
  EXPECT_EQ(json["scans"].size(), 2u);
  EXPECT_EQ(json["scans"][1]["path"].size(), scans[1].path.size());
  const OctomapImport map = read_octomap(dir / "map.bt", OctomapImportConfig{});
  EXPECT_GT(map.known_voxels, 0u);
  const auto floor = parse_csv(read_text(dir / "floor_map.txt"));
  EXPECT_EQ(floor.size(), 1u + 40u);  // the header line and one row per y
}

TEST(Office, SameSeedSameCsvForOneAndTwoThreads) {
  for (const PlannerMethod method : {PlannerMethod::kYamauchi, PlannerMethod::kRandom}) {
    const OfficeRun one = office_run(method, 1);
    const OfficeRun two = office_run(method, 2);
    EXPECT_EQ(testing::without_timing(one.csv), testing::without_timing(two.csv))
        << to_string(method);
  }
}

TEST(Office, EveryMethodDrivesToAFrontierStop) {
  for (const PlannerMethod method : {PlannerMethod::kGreedy, PlannerMethod::kLatombe}) {
    const OfficeRun run = office_run(method, 0);
    ASSERT_EQ(run.result.scans.size(), 2u) << to_string(method);
    EXPECT_GT(run.result.scans[1].travel, 0.0) << to_string(method);
    EXPECT_GT(*run.result.scans[1].greedy_predicted_gain, 0.0) << to_string(method);
  }
}

TEST(Office, SweepFrustaTileTheSweepWithoutOverlap) {
  const sim::Scene scene = sim::load_scene(office_path());
  const Eigen::Isometry3d pose = scene.mount.sensor_pose(2.0, 2.0, 0.3);
  const std::vector<Frustum> frusta = sweep_frusta(scene, pose);
  ASSERT_EQ(frusta.size(), static_cast<std::size_t>(scene.sensor.sweep_steps));
  // The real steps are wider (57 degrees) and overlap; a point is seen by the sweep iff one of
  // them holds it, and then exactly one planning frustum holds it.
  std::vector<Frustum> steps;
  for (const Frustum& f : frusta) steps.emplace_back(f.T_world_sensor(), scene.fov());
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  int seen = 0;
  for (int k = 0; k < 20000; ++k) {
    const Eigen::Vector3d p = pose.translation() + Eigen::Vector3d(u(rng), u(rng), u(rng) / 4);
    int planning = 0, real = 0;
    for (const Frustum& f : frusta) planning += f.contains(p);
    for (const Frustum& f : steps) real += f.contains(p);
    EXPECT_LE(planning, 1) << p.transpose();
    EXPECT_EQ(planning == 1, real > 0) << p.transpose();
    seen += planning;
  }
  EXPECT_GT(seen, 1000);
}

TEST(Office, BenchDefaultsAreThePapers) {
  const BenchConfig config = office_bench_config();
  EXPECT_EQ(config.scenes.size(), 4u);
  EXPECT_EQ(config.methods.size(), 5u);
  EXPECT_EQ(config.trials, 5);
  EXPECT_EQ(config.alphas, (std::vector<AlphaSetting>{{false, 0.9999}, {false, 0.999}}));
  EXPECT_EQ(bench_trials(config).size(), 4u * (2u + 4u) * 5u);
}

}  // namespace
}  // namespace vantage
