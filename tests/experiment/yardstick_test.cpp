// The yardstick of issue 36: surface coverage by scan points against a box worked out by hand,
// the denominator against the union of the noise-free hits of the candidates and starts, and the
// greedy oracle against greedy on the small table top.

#include "vantage/experiment/yardstick.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <stdexcept>
#include <tuple>

#include "test_scene.hpp"
#include "vantage/experiment/bench.hpp"
#include "vantage/experiment/exploration.hpp"
#include "vantage/experiment/results.hpp"
#include "vantage/sim/ground_truth.hpp"

namespace vantage {
namespace {

// A 10 x 10 x 10 grid of 0.1 m cells from the origin, and a solid box of cells 2..5 on every
// axis: 64 cells, of which the 8 of 3..4 on every axis are interior, so 56 are surface.
struct BoxCase {
  GridSpec grid;
  std::vector<std::uint8_t> occupied;
  BoxCase() {
    grid.origin = Eigen::Vector3d::Zero();
    grid.resolution = 0.1;
    grid.dims = Index3(10, 10, 10);
    occupied.assign(grid.num_cells(), 0);
    for (int z = 2; z <= 5; ++z) {
      for (int y = 2; y <= 5; ++y) {
        for (int x = 2; x <= 5; ++x) occupied[grid.linear({x, y, z})] = 1;
      }
    }
  }
  std::uint32_t id(int x, int y, int z) const {
    return static_cast<std::uint32_t>(grid.linear({x, y, z}));
  }
  /// Points at the centres of the face cells' (a, b) across a face, at `depth` on its normal axis.
  PointCloud face(int axis, double depth) const {
    PointCloud points;
    for (int a = 2; a <= 5; ++a) {
      for (int b = 2; b <= 5; ++b) {
        Eigen::Vector3d p;
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        p[axis] = depth;
        p[u] = 0.1 * a + 0.05;
        p[v] = 0.1 * b + 0.05;
        points.push_back(p);
      }
    }
    return points;
  }
};

TEST(Yardstick, BoxSeenFromTwoSidesCoversTheCellsWorkedOutByHand) {
  const BoxCase box;
  const std::vector<std::uint32_t> surface = sim::surface_cells(box.grid, box.occupied);
  ASSERT_EQ(surface.size(), 56u);

  // Seen from -x, the points 1 cm in front of the face (in the cells x = 1): the face layer
  // x = 2 is within one cell, the layer behind it (x = 3) is not.
  PointCloud points = box.face(0, 0.19);
  std::vector<std::uint32_t> covered = covered_cells(box.grid, surface, points);
  EXPECT_EQ(covered.size(), 16u);
  for (const std::uint32_t c : covered) EXPECT_EQ(box.grid.unravel(c).x(), 2);

  // ... and from +y, 1 cm in front of the face y = 5: 16 more, less the 4 cells of the edge
  // both faces share (x = 2, y = 5).
  const PointCloud from_y = box.face(1, 0.61);
  points.insert(points.end(), from_y.begin(), from_y.end());
  covered = covered_cells(box.grid, surface, points);
  EXPECT_EQ(covered.size(), 28u);
  for (const std::uint32_t c : covered) {
    const Index3 q = box.grid.unravel(c);
    EXPECT_TRUE(q.x() == 2 || q.y() == 5) << q.transpose();
  }

  // A point inside the face cells (1 cm behind the face) reaches the next layer too: its
  // surface ring (12 cells of x = 3; its 4 interior-facing cells are not surface).
  EXPECT_EQ(covered_cells(box.grid, surface, box.face(0, 0.21)).size(), 16u + 12u);
  // Two cells away (x = 0) is too far.
  EXPECT_TRUE(covered_cells(box.grid, surface, box.face(0, 0.09)).empty());
  // Outside the grid next to a border cell still counts (the grid's own border is not a wall).
  BoxCase border;
  std::vector<std::uint32_t> corner{border.id(0, 0, 0)};
  EXPECT_EQ(covered_cells(border.grid, corner, {Eigen::Vector3d(-0.05, 0.05, 0.05)}).size(), 1u);
  EXPECT_TRUE(covered_cells(border.grid, corner, {Eigen::Vector3d(-0.15, 0.05, 0.05)}).empty());

  // The two shares: the visible surface here is the faces x = 2 and x = 5 (32 cells), of which
  // the -x scan covers one face; the raw share is over all 56.
  SurfaceTruth truth;
  truth.grid = box.grid;
  truth.surface = surface;
  for (const std::uint32_t c : surface) {
    const int x = box.grid.unravel(c).x();
    if (x == 2 || x == 5) truth.visible.push_back(c);
  }
  ASSERT_EQ(truth.visible.size(), 32u);
  const SurfaceCoverage s = surface_coverage(truth, box.face(0, 0.19));
  EXPECT_DOUBLE_EQ(s.visible, 16.0 / 32.0);
  EXPECT_DOUBLE_EQ(s.raw, 16.0 / 56.0);
  EXPECT_EQ(s.covered.size(), 16u);
  const SurfaceCoverage both = surface_coverage(truth, points);  // -x and +y
  EXPECT_DOUBLE_EQ(both.visible, 16.0 / 32.0 + 4.0 / 32.0);      // + y = 5 on the x = 5 face
  EXPECT_DOUBLE_EQ(both.raw, 28.0 / 56.0);
}

TEST(Yardstick, CountCommonCountsTheIntersection) {
  EXPECT_EQ(
      count_common(std::vector<std::uint32_t>{1, 3, 5, 7}, std::vector<std::uint32_t>{3, 4, 7}),
      2u);
  EXPECT_EQ(count_common(std::vector<std::uint32_t>{}, std::vector<std::uint32_t>{3}), 0u);
}

class YardstickAtTolerance : public ::testing::TestWithParam<int> {};

TEST_P(YardstickAtTolerance, DenominatorIsTheUnionOfTheCandidatesAndStartsNoiseFreeHits) {
  const int tolerance = GetParam();
  const sim::Scene scene = sim::load_scene(testing::small_scene_path());
  const sim::World world(scene, sim::WorldConfig{2});
  const std::vector<Eigen::Isometry3d> candidates = scene.candidate_poses();
  const SurfaceTruth truth = compute_surface_truth(world, candidates, tolerance, 2);
  ASSERT_EQ(truth.candidate_hits.size(), candidates.size());
  EXPECT_EQ(truth.tolerance, tolerance);
  const SurfaceTruth one_thread = compute_surface_truth(world, candidates, tolerance, 1);
  EXPECT_EQ(one_thread.visible, truth.visible);
  EXPECT_EQ(one_thread.candidate_hits, truth.candidate_hits);
  ASSERT_EQ(truth.start_hits.size(), scene.start_poses.size());

  // The union, worked out here from the scans' points one by one: the cells of the points off
  // the table and floor, and every surface cell with one of them among its 27.
  Eigen::AlignedBox3d table;
  for (const sim::Shape& s : scene.shapes) {
    if (s.kind == "table" || s.kind == "floor") table.extend(s.bounds());
  }
  ASSERT_FALSE(table.isEmpty());
  sim::SensorConfig sensor = scene.sensor;
  sensor.noise = sim::RangeNoise{};
  std::vector<Eigen::Isometry3d> poses = candidates;
  poses.insert(poses.end(), scene.start_poses.begin(), scene.start_poses.end());
  std::set<std::uint32_t> hit;
  std::size_t dropped = 0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    std::set<std::tuple<int, int, int>> point_cells;
    for (const Eigen::Vector3d& p : world.scan(poses[k], sensor, 7).points_sensor) {
      const Eigen::Vector3d w = poses[k] * p;
      if (table.contains(w) || w.z() <= table.max().z() + 1e-6) {
        ++dropped;
        continue;
      }
      const Index3 c = scene.grid.lattice_index(w);
      point_cells.emplace(c.x(), c.y(), c.z());
    }
    std::vector<std::uint32_t> mine;
    for (const std::uint32_t cell : truth.surface) {
      const Index3 c = scene.grid.unravel(cell);
      bool near = false;
      for (int dz = -tolerance; dz <= tolerance; ++dz) {
        for (int dy = -tolerance; dy <= tolerance; ++dy) {
          for (int dx = -tolerance; dx <= tolerance; ++dx) {
            near = near || point_cells.count({c.x() + dx, c.y() + dy, c.z() + dz}) > 0;
          }
        }
      }
      if (near) mine.push_back(cell);
    }
    const auto& given =
        k < candidates.size() ? truth.candidate_hits[k] : truth.start_hits[k - candidates.size()];
    EXPECT_EQ(given, mine) << "pose " << k;
    hit.insert(mine.begin(), mine.end());
  }
  EXPECT_GT(dropped, 0u);  // the table was in view
  EXPECT_EQ(truth.visible, std::vector<std::uint32_t>(hit.begin(), hit.end()));
  EXPECT_GT(truth.visible.size(), truth.surface.size() / 4);
  // NOTE: at 1/32 m a cell's 26 neighbours reach the undersides of these small objects: here
  // every surface cell is within one cell of a hit.
  EXPECT_LE(truth.visible.size(), truth.surface.size());

  // The table is not object surface: no surface cell lies outside the objects' own voxels.
  const std::vector<std::uint8_t> all = sim::voxelize(scene.shapes, scene.grid, 2);
  for (const std::uint32_t c : truth.surface) EXPECT_EQ(all[c], 1);
  std::vector<sim::Shape> objects;
  for (const sim::Shape& s : scene.shapes) {
    if (s.kind != "table" && s.kind != "floor") objects.push_back(s);
  }
  EXPECT_EQ(truth.surface, sim::surface_cells(scene.grid, sim::voxelize(objects, scene.grid, 2)));
}

INSTANTIATE_TEST_SUITE_P(InACellAndWithinOne, YardstickAtTolerance, ::testing::Values(0, 1));

TEST(Yardstick, AtToleranceZeroOnlyTheCellAPointLiesInIsCovered) {
  const BoxCase box;
  const std::vector<std::uint32_t> surface = sim::surface_cells(box.grid, box.occupied);
  // 1 cm in front of the face, in the cells x = 1: within one cell of the face, in none of it.
  EXPECT_EQ(covered_cells(box.grid, surface, box.face(0, 0.19), 1).size(), 16u);
  EXPECT_TRUE(covered_cells(box.grid, surface, box.face(0, 0.19), 0).empty());
  // 1 cm behind the face, in its cells x = 2: exactly those 16, not the layer behind (x = 3).
  const std::vector<std::uint32_t> in_face = covered_cells(box.grid, surface, box.face(0, 0.21), 0);
  EXPECT_EQ(in_face.size(), 16u);
  for (const std::uint32_t c : in_face) EXPECT_EQ(box.grid.unravel(c).x(), 2);
  // ... and from +y, 1 cm inside the face y = 5: 16 more less the shared edge x = 2, y = 5.
  PointCloud points = box.face(0, 0.21);
  const PointCloud from_y = box.face(1, 0.59);
  points.insert(points.end(), from_y.begin(), from_y.end());
  EXPECT_EQ(covered_cells(box.grid, surface, points, 0).size(), 28u);
  // A point just outside the grid covers nothing at tolerance 0.
  std::vector<std::uint32_t> corner{box.id(0, 0, 0)};
  EXPECT_TRUE(covered_cells(box.grid, corner, {Eigen::Vector3d(-0.05, 0.05, 0.05)}, 0).empty());
  EXPECT_THROW(covered_cells(box.grid, surface, points, 2), std::invalid_argument);

  SurfaceTruth truth;
  truth.grid = box.grid;
  truth.tolerance = 0;
  truth.surface = surface;
  truth.visible = surface;
  EXPECT_DOUBLE_EQ(surface_coverage(truth, points).visible, 28.0 / 56.0);
  // At 1 the points reach the next layer in too: every surface cell with x in {2, 3} or y in
  // {4, 5}, all but the 14 with x in {4, 5} and y in {2, 3} (8 on the face x = 5, 6 at x = 4).
  truth.tolerance = 1;
  EXPECT_DOUBLE_EQ(surface_coverage(truth, points).visible, 42.0 / 56.0);
}

/// The first scan of `scans` whose surface coverage reaches `level`, or infinity.
double scans_to(const std::vector<ScanRecord>& scans, double level) {
  for (const ScanRecord& r : scans) {
    if (r.surface_coverage && *r.surface_coverage >= level) return r.scan;
  }
  return std::numeric_limits<double>::infinity();
}

TEST(Yardstick, GreedyOracleNeverNeedsMoreScansThanGreedyOnTheSmallTableTop) {
  const sim::Scene scene = sim::load_scene(testing::small_scene_path());
  const sim::World world(scene, sim::WorldConfig{2});
  const SurfaceTruth truth = compute_surface_truth(world, scene.candidate_poses(), 1, 2);
  for (int start = 0; start < 3; ++start) {
    std::vector<ScanRecord> runs[2];
    for (const bool oracle : {false, true}) {
      ExplorationConfig config;
      config.planner.method = PlannerMethod::kGreedy;
      config.planner.gain.num_threads = 2;
      config.greedy_oracle = oracle;
      config.scans = 5;
      config.start = start;
      // NOTE: without pose noise. With it, the oracle's view (the one sharing least with the
      // map) is the one registration most often cannot pin: on start 2 its second scan fell
      // back with a 7 cm pose error, and greedy's better-anchored view covered more (RESULTS.md).
      config.pose_noise = sim::PoseNoise{0.0, 0.0, 0.0};
      config.mapper = default_mapper_config(scene);
      Mapper mapper(scene.grid, config.mapper);
      runs[oracle ? 1 : 0] = explore(scene, config, mapper, {}, &truth).scans;
    }
    const std::vector<ScanRecord>& greedy = runs[0];
    const std::vector<ScanRecord>& oracle = runs[1];
    ASSERT_EQ(oracle.size(), 5u);
    for (const ScanRecord& r : oracle) {
      ASSERT_TRUE(r.surface_coverage && r.raw_surface_coverage);
      // The covered cells of V are covered cells of S.
      EXPECT_LE(*r.surface_coverage * static_cast<double>(truth.visible.size()),
                *r.raw_surface_coverage * static_cast<double>(truth.surface.size()) + 1e-6);
    }
    for (std::size_t k = 1; k < oracle.size(); ++k) {
      EXPECT_GE(*oracle[k].surface_coverage, *oracle[k - 1].surface_coverage);
      // The oracle's gain is the chosen view's true new cells: the largest of its decision.
      for (const CandidateRecord& c : oracle[k].considered) {
        EXPECT_LE(c.predicted_gain, *oracle[k].predicted_gain);
      }
    }
    for (const double level : {0.5, 0.6, 0.7, 0.8, 0.85, 0.9, 0.95}) {
      EXPECT_LE(scans_to(oracle, level), scans_to(greedy, level))
          << "start " << start << ", level " << level;
    }
    EXPECT_GE(*oracle[2].surface_coverage, *greedy[2].surface_coverage) << "start " << start;
  }
}

TEST(Yardstick, TheGreedyOracleChoosesByTheTruthAloneWhateverTheNoise) {
  const sim::Scene scene = sim::load_scene(testing::small_scene_path());
  const sim::World world(scene, sim::WorldConfig{2});
  const std::vector<Eigen::Isometry3d> candidates = scene.candidate_poses();
  const SurfaceTruth truth = compute_surface_truth(world, candidates, 1, 2);
  ExplorationConfig config;
  config.planner.method = PlannerMethod::kGreedy;
  config.greedy_oracle = true;
  config.scans = 4;
  config.start = 2;
  config.mapper = default_mapper_config(scene);
  const TravelRule travel = run_travel_rule(scene, config);

  // Greedy on the true hit sets, worked out here: the most new cells, then the shorter travel.
  std::set<std::uint32_t> hit(truth.start_hits[2].begin(), truth.start_hits[2].end());
  std::vector<bool> taken(candidates.size(), false);
  Eigen::Vector3d here = scene.start_poses[2].translation();
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (candidates[i].isApprox(scene.start_poses[2], 1e-9)) taken[i] = true;
  }
  std::vector<int> expected;
  for (int k = 1; k < config.scans; ++k) {
    int best = -1;
    std::size_t best_gain = 0;
    double best_travel = 0.0;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      if (taken[i]) continue;
      std::size_t gain = 0;
      for (const std::uint32_t c : truth.candidate_hits[i]) gain += hit.count(c) == 0;
      const double t = travel(here, candidates[i].translation());
      if (best < 0 || gain > best_gain || (gain == best_gain && t < best_travel)) {
        best = static_cast<int>(i);
        best_gain = gain;
        best_travel = t;
      }
    }
    expected.push_back(best);
    taken[static_cast<std::size_t>(best)] = true;
    hit.insert(truth.candidate_hits[best].begin(), truth.candidate_hits[best].end());
    here = candidates[static_cast<std::size_t>(best)].translation();
  }

  // With and without pose noise (and so with and without registration's misses), the same views.
  for (const bool noisy : {true, false}) {
    ExplorationConfig c = config;
    if (!noisy) c.pose_noise = sim::PoseNoise{0.0, 0.0, 0.0};
    Mapper mapper(scene.grid, c.mapper);
    std::vector<int> views;
    for (const ScanRecord& r : explore(scene, c, mapper, {}, &truth).scans) {
      if (r.scan > 1) views.push_back(r.view);
    }
    EXPECT_EQ(views, expected) << (noisy ? "with" : "without") << " pose noise";
  }
}

TEST(Yardstick, ASweepRunsTheGreedyOracleAndWritesTheTruthForTheSetCover) {
  BenchConfig config;
  config.scenes = {testing::small_scene_path()};
  config.methods = {PlannerMethod::kGreedy};
  config.greedy_oracle = true;
  config.trials = 1;
  config.exploration.scans = 3;
  config.exploration.planner.gain.num_threads = 2;
  const auto dir = testing::fresh_dir("bench-oracle");
  EXPECT_EQ(run_bench(dir, config), 2u);
  const auto rows = testing::parse_csv(testing::read_text(dir / "scans.csv"));
  ASSERT_EQ(rows.size(), 7u);
  EXPECT_EQ(rows[0][27], "surface_coverage");
  EXPECT_EQ(rows[0][28], "raw_surface_coverage");
  std::set<std::string> methods;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    methods.insert(rows[k][1]);
    ASSERT_EQ(rows[k].size(), 29u);
    EXPECT_GT(std::stod(rows[k][27]), 0.0);
    EXPECT_LE(std::stod(rows[k][27]), 1.0);
  }
  EXPECT_EQ(methods, (std::set<std::string>{"greedy", "greedy-oracle"}));

  const auto file =
      nlohmann::json::parse(testing::read_text(dir / kYardstickFolder / "small-tabletop.json"));
  EXPECT_EQ(file["views"].size(), 30u);
  EXPECT_EQ(file["travel_m"]["views"].size(), 30u);
  EXPECT_EQ(file["travel_m"]["from_starts"].size(), file["starts"].size());
  std::set<std::size_t> seen;
  for (const auto& set : {file["views"], file["starts"]}) {
    for (const auto& view : set) {
      for (const auto& cell : view) seen.insert(cell.get<std::size_t>());
    }
  }
  EXPECT_EQ(seen.size(), file["visible_cells"].get<std::size_t>());  // V is their union
  EXPECT_EQ(*seen.rbegin() + 1, seen.size());                        // indices 0 .. |V| - 1

  // An office has no fixed candidates: a sweep with the oracle is refused before any trial.
  BenchConfig office = config;
  office.scenes = {(testing::source_dir() / "tests/experiment/small_office.yaml").string()};
  const auto office_dir = testing::fresh_dir("bench-oracle-office");
  EXPECT_THROW(run_bench(office_dir, office), std::invalid_argument);
  EXPECT_TRUE(std::filesystem::is_empty(office_dir / "trials"));

  // A merge carries the yardstick's truth along.
  const auto merged = testing::fresh_dir("bench-oracle-merged");
  merge_bench({dir}, merged);
  EXPECT_EQ(testing::read_text(merged / kYardstickFolder / "small-tabletop.json"),
            testing::read_text(dir / kYardstickFolder / "small-tabletop.json"));

  // A trial file from before the surface columns joins the sweep's CSV with them empty.
  const std::string old_row =
      "small-tabletop,random,,0,1,0,,,10,100,0.5,0,0,0,,,,0,0,0,0,0,0,0,0,0,0\n";
  testing::write_text(dir / "trials" / "small-tabletop__random__t0.csv", old_row);
  write_bench_csv(dir);
  bool found = false;
  for (const auto& row : testing::parse_csv(testing::read_text(dir / "scans.csv"))) {
    if (row[1] != "random") continue;
    found = true;
    ASSERT_EQ(row.size(), 29u);
    EXPECT_EQ(row[27], "");
  }
  EXPECT_TRUE(found);
}

}  // namespace
}  // namespace vantage

namespace vantage {
namespace {

// PB-NBV's rule, a point within a distance of the cell: against every cell's box measured pair by
// pair, on random points in and around a small grid.
TEST(Yardstick, ADistanceToleranceCoversTheCellsWithinItOfAPoint) {
  const GridSpec grid = GridSpec::centered({0.1, -0.2, 0.3}, 0.005, {9, 7, 8});
  std::vector<std::uint32_t> all(grid.num_cells());
  for (std::uint32_t c = 0; c < all.size(); ++c) all[c] = c;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.03, 0.03);
  for (const double metres : {0.001, 0.005, 0.0123}) {
    PointCloud points;
    for (int k = 0; k < 12; ++k)
      points.push_back(Eigen::Vector3d(0.1 + u(rng), -0.2 + u(rng), 0.3 + u(rng)));
    std::vector<std::uint32_t> expected;
    for (const std::uint32_t c : all) {
      const Eigen::Vector3d lo = grid.origin + grid.resolution * grid.unravel(c).cast<double>();
      const Eigen::AlignedBox3d box(lo, lo + Eigen::Vector3d::Constant(grid.resolution));
      for (const Eigen::Vector3d& p : points) {
        if (box.exteriorDistance(p) <= metres) {
          expected.push_back(c);
          break;
        }
      }
    }
    EXPECT_EQ(covered_cells(grid, all, points, CoverageTolerance::within(metres)), expected)
        << metres << " m";
    EXPECT_FALSE(expected.empty());
  }
  EXPECT_EQ(parse_coverage_tolerance("5mm"), CoverageTolerance::within(0.005));
  EXPECT_EQ(parse_coverage_tolerance("0.005m"), CoverageTolerance::within(0.005));
  EXPECT_EQ(parse_coverage_tolerance("0"), CoverageTolerance(0));
  for (const char* bad : {"5", "mm", "-1mm", "2m", "5 mm", "1e400mm"}) {
    EXPECT_THROW(parse_coverage_tolerance(bad), std::invalid_argument) << bad;
  }
}

}  // namespace
}  // namespace vantage
