// A simulated sequence written to disk as clouds and a manifest, mapped and planned from the
// files, ranks the candidates as the in-process pipeline does.

#include "vantage/experiment/recorded.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <numeric>
#include <string>

#include "test_scene.hpp"
#include "vantage/experiment/exploration.hpp"
#include "vantage/io/cloud_io.hpp"
#include "vantage/io/octomap_io.hpp"
#include "vantage/sim/world.hpp"

namespace vantage {
namespace {

std::vector<std::size_t> ranking(const Plan& plan) {
  std::vector<std::size_t> order(plan.scores.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return plan.scores[a] > plan.scores[b]; });
  return order;
}

// Both maps rank the scene's candidates identically, with the same gains to the last bit (the
// method's and greedy's).
void expect_same_decision(const sim::Scene& scene, const OccupancyGrid& expected,
                          const OccupancyGrid& got) {
  std::vector<Candidate> candidates;
  for (const Eigen::Isometry3d& pose : scene.candidate_poses()) {
    candidates.push_back({Frustum(pose, scene.fov())});
  }
  PlannerConfig planner;
  planner.greedy_reference = true;
  const Plan a = plan_next_view(expected, candidates, planner);
  const Plan b = plan_next_view(got, candidates, planner);
  EXPECT_EQ(a.best, b.best);
  EXPECT_EQ(ranking(a), ranking(b));
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    EXPECT_EQ(a.gains[i].gain, b.gains[i].gain) << "candidate " << i;
    EXPECT_EQ(a.greedy_gains[i], b.greedy_gains[i]) << "candidate " << i;
  }
}

TEST(Recorded, PlanningFromFilesRanksAsInProcess) {
  const sim::Scene scene = sim::load_scene(testing::small_scene_path());
  const sim::World world(scene);
  MapperConfig config;
  config.register_scans = false;  // poses are exact here; ICP has its own tests
  config.segment_table = true;

  const std::filesystem::path dir = testing::fresh_dir("recorded");
  Manifest manifest;
  manifest.frame = CloudFrame::kXForward;
  manifest.fov = scene.fov();
  manifest.roi = Eigen::AlignedBox3d(scene.grid.origin, scene.grid.max_corner());
  manifest.grid = scene.grid;
  manifest.options.table_segmentation = true;

  Mapper in_process(scene.grid, config);
  for (const std::size_t start : {0u, 4u}) {
    sim::SimulatedScan scan = world.scan(scene.start_poses[start], 11 + start);
    // NOTE: PCD stores float32; rounding here too makes both paths see the same points, so any
    // difference would come from the files, the manifest or the frames.
    for (Eigen::Vector3d& p : scan.points_sensor) p = p.cast<float>().cast<double>();
    in_process.add_scan(scan.points_sensor, scan.T_world_sensor_true, scan.fov);
    ManifestCloud cloud;
    cloud.file = dir / ("scan" + std::to_string(start) + ".pcd");
    cloud.T_world_cloud = cloud.T_world_sensor = scan.T_world_sensor_true;
    write_point_cloud(cloud.file, scan.points_sensor);
    manifest.clouds.push_back(cloud);
  }
  write_manifest(dir / "manifest.yaml", manifest);

  const Manifest read = read_manifest(dir);
  ASSERT_EQ(read.clouds.size(), 2u);
  MapperConfig from_manifest = mapper_config_for(read);
  EXPECT_TRUE(from_manifest.segment_table);
  EXPECT_FALSE(from_manifest.register_scans);
  Mapper from_files(read.grid, from_manifest);
  map_recorded(read, from_files);

  expect_same_decision(scene, in_process.grid(), from_files.grid());
}

// The robot's loop: scan, plan, save the map, move, scan, plan from the saved map. Continuing from
// map.ot must be exactly mapping every scan in one go: the same log-odds in every cell, the same
// gains to the last bit, the same ranking. map.bt, which keeps classes only, must not be (else
// this test could not tell the two apart).
TEST(Recorded, ContinuingFromMapOtIsMappingEveryScanAtOnce) {
  const sim::Scene scene = sim::load_scene(testing::small_scene_path());
  const sim::World world(scene);
  MapperConfig config;
  config.register_scans = false;  // a saved map carries no points for ICP to register against
  config.segment_table = true;
  std::vector<sim::SimulatedScan> scans;
  for (const std::size_t start : {0u, 3u, 6u}) {
    scans.push_back(world.scan(scene.start_poses[start], 21 + start));
  }

  Mapper at_once(scene.grid, config);
  for (const sim::SimulatedScan& scan : scans) {
    at_once.add_scan(scan.points_sensor, scan.T_world_sensor_true, scan.fov);
  }

  const std::filesystem::path dir = testing::fresh_dir("recorded_loop");
  auto continued = [&](const std::string& extension) {
    Mapper mapper(scene.grid, config);
    for (std::size_t k = 0; k < scans.size(); ++k) {
      if (k > 0) {
        const std::filesystem::path saved = dir / ("step" + std::to_string(k) + extension);
        write_octomap(saved, mapper.grid());
        OctomapImportConfig import;
        import.grid = scene.grid;
        mapper = Mapper(read_octomap(saved, import).grid, config);
      }
      mapper.add_scan(scans[k].points_sensor, scans[k].T_world_sensor_true, scans[k].fov);
    }
    return mapper;
  };
  const Mapper from_ot = continued(".ot");
  const Mapper from_bt = continued(".bt");

  const std::span<const float> expected = at_once.grid().log_odds();
  const std::span<const float> got = from_ot.grid().log_odds();
  ASSERT_EQ(got.size(), expected.size());
  EXPECT_EQ(std::memcmp(got.data(), expected.data(), got.size_bytes()), 0)
      << "the map continued from map.ot differs from the map of every scan";
  EXPECT_NE(std::memcmp(from_bt.grid().log_odds().data(), expected.data(), got.size_bytes()), 0);

  expect_same_decision(scene, at_once.grid(), from_ot.grid());
}

TEST(Recorded, NanPixelsFailUnlessTheManifestSkipsThem) {
  const sim::Scene scene = sim::load_scene(testing::small_scene_path());
  const sim::World world(scene);
  sim::SimulatedScan scan = world.scan(scene.start_poses[0], 5);
  for (Eigen::Vector3d& p : scan.points_sensor) p = p.cast<float>().cast<double>();

  // An organized cloud's layout: the scan's points with a NaN pixel after every tenth.
  const std::filesystem::path dir = testing::fresh_dir("recorded_nan");
  {
    std::ofstream pcd(dir / "organized.pcd");
    const std::size_t n = scan.points_sensor.size(), holes = (n + 9) / 10;
    pcd << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " << n + holes
        << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << n + holes << "\nDATA ascii\n";
    pcd.precision(9);
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d& p = scan.points_sensor[i];
      pcd << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
      if (i % 10 == 0) pcd << "nan nan nan\n";
    }
  }
  Manifest manifest;
  manifest.frame = CloudFrame::kXForward;
  manifest.fov = scene.fov();
  manifest.roi = Eigen::AlignedBox3d(scene.grid.origin, scene.grid.max_corner());
  manifest.grid = scene.grid;
  ManifestCloud cloud;
  cloud.file = dir / "organized.pcd";
  cloud.T_world_cloud = cloud.T_world_sensor = scan.T_world_sensor_true;
  manifest.clouds.push_back(cloud);
  MapperConfig config;
  config.register_scans = false;
  config.segment_table = false;

  Mapper refused(scene.grid, config);
  try {
    map_recorded(manifest, refused);
    FAIL() << "a NaN point was accepted without skip_non_finite";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("organized.pcd"), std::string::npos) << e.what();
    // issue 27: the message points to the manifest's switch.
    EXPECT_NE(std::string(e.what()).find("set options.skip_non_finite: true"), std::string::npos)
        << e.what();
  }

  manifest.options.skip_non_finite = true;
  write_manifest(dir / "manifest.yaml", manifest);
  const Manifest read = read_manifest(dir);
  EXPECT_TRUE(read.options.skip_non_finite);
  Mapper skipped(scene.grid, config);
  std::size_t non_finite = 0;
  map_recorded(read, skipped, [&](const RecordedCloud& c) { non_finite += c.non_finite_skipped; });
  EXPECT_EQ(non_finite, (scan.points_sensor.size() + 9) / 10);  // the callback counts them
  Mapper direct(scene.grid, config);
  direct.add_scan(scan.points_sensor, scan.T_world_sensor_true, scan.fov);
  ASSERT_EQ(skipped.grid().spec().num_cells(), direct.grid().spec().num_cells());
  for (std::size_t i = 0; i < direct.grid().spec().num_cells(); ++i) {
    ASSERT_EQ(skipped.grid().log_odds(i), direct.grid().log_odds(i)) << "cell " << i;
  }
}

}  // namespace
}  // namespace vantage
