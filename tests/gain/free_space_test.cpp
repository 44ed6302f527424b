// The free space of a grid (vantage/gain/free_space.hpp) against a brute-force distance, and the
// rays that cross its cubes in one step against the same rays walked cell by cell: the exact
// lists' visibilities bit for bit, the swept estimate to rounding; the grid's classes
// (vantage/gain/class_map.hpp) against the snapshot's, and the samples and lists read from them.

#include "vantage/gain/free_space.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <vector>

#include "vantage/gain/class_map.hpp"
#include "vantage/gain/evaluators/exact.hpp"
#include "vantage/gain/evaluators/swept.hpp"
#include "vantage/gain/evaluators/view_cells.hpp"
#include "vantage/gain/models/target_predictors.hpp"
#include "vantage/gain/snapshot.hpp"

namespace vantage {
namespace {

/// A 0.78 x 0.72 x 0.56 m grid of 2 cm cells, free but for unobserved boxes and occupied
/// specks (fixed seed): free cubes of many sizes, and blocks cut by the grid's far faces.
OccupancyGrid cluttered() {
  GridSpec spec;
  spec.origin = {-0.4, -0.36, -0.28};
  spec.resolution = 0.02;
  spec.dims = {39, 36, 28};
  OccupancyGrid grid(spec);
  for (std::size_t i = 0; i < grid.size(); ++i) grid.miss(i);
  std::mt19937 rng(17);
  std::uniform_int_distribution<int> x(0, 38), y(0, 35), z(0, 27), size(1, 7);
  for (int k = 0; k < 12; ++k) {
    const Index3 lo(x(rng), y(rng), z(rng));
    const Index3 hi =
        (lo + Index3(size(rng), size(rng), size(rng))).cwiseMin(spec.dims - Index3::Ones());
    for (int c = lo.z(); c <= hi.z(); ++c) {
      for (int b = lo.y(); b <= hi.y(); ++b) {
        for (int a = lo.x(); a <= hi.x(); ++a) grid.set_log_odds(spec.linear({a, b, c}), 0.0f);
      }
    }
  }
  for (int k = 0; k < 25; ++k) grid.set_probability(spec.linear({x(rng), y(rng), z(rng)}), 0.9);
  return grid;
}

TEST(FreeSpace, AnExtentIsTheLargestAllFreeCubeAheadInItsOctant) {
  const OccupancyGrid grid = cluttered();
  const FreeSpace free = free_space(grid.census());
  const GridSpec& spec = grid.spec();
  ASSERT_EQ(free.dims, Index3(10, 9, 7));
  // Blocks not all free, from the cells.
  const auto n = static_cast<std::size_t>(free.dims.prod());
  std::vector<bool> mixed(n, false);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (grid.state(i) != CellState::kFree) mixed[grid.census().block_of(spec.unravel(i))] = true;
  }
  const auto block = [&](std::size_t b) {
    const auto nx = static_cast<std::size_t>(free.dims.x());
    const auto ny = static_cast<std::size_t>(free.dims.y());
    return Index3(static_cast<int>(b % nx), static_cast<int>(b / nx % ny),
                  static_cast<int>(b / (nx * ny)));
  };
  int cubes = 0;
  for (int o = 0; o < 8; ++o) {
    const Index3 sign((o & 1) ? 1 : -1, (o & 2) ? 1 : -1, (o & 4) ? 1 : -1);
    for (std::size_t b = 0; b < n; ++b) {
      // Brute force: one more than the least Chebyshev distance to a block not all free among
      // those ahead of b in octant o (every offset's component of o's sign or 0).
      int expected = 0;
      if (!mixed[b]) {
        expected = 255;
        for (std::size_t m = 0; m < n; ++m) {
          const Index3 k = (block(m) - block(b)).cwiseProduct(sign);
          if (mixed[m] && (k.array() >= 0).all()) expected = std::min(expected, k.maxCoeff());
        }
      }
      ASSERT_EQ(free.extent[static_cast<std::size_t>(o)][b], expected)
          << "octant " << o << " block " << b;
      cubes += expected >= 3;
    }
  }
  EXPECT_GT(cubes, 40);  // the grid has cubes worth crossing
}

TEST(FreeSpace, RaysThatCrossFreeCubesSeeWhatCellByCellRaysSee) {
  const OccupancyGrid grid = cluttered();
  const ClassMap map(grid);
  const GainMap snapshot(grid, 1);
  const GridSpec& spec = map.spec();
  std::vector<Index3> targets;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (grid.state(i) == CellState::kUnobserved) targets.push_back(spec.unravel(i));
  }
  ASSERT_GT(targets.size(), 500u);
  int seen = 0;
  for (const Eigen::Vector3d& origin :
       {Eigen::Vector3d(-0.39, -0.35, -0.27), Eigen::Vector3d(0.05, 0.01, 0.02),
        Eigen::Vector3d(0.9, -0.7, 0.5)}) {
    const int longest = max_ray_cells(spec, origin);
    const SurvivalModel model(0.9, grid.params().p_min, longest);
    for (const Index3& t : targets) {
      const TargetPrediction cells = detail::SurvivalVisibilityPredictor{0.9, 1e-6}(map, origin, t);
      const TargetPrediction cubes =
          detail::SurvivalVisibilityPredictor{0.9, 1e-6, &map.free_space()}(map, origin, t);
      ASSERT_EQ(cubes.seen, cells.seen) << t.transpose();
      // The survival reading's own v_M, bit for bit.
      ASSERT_EQ(cells.seen, (detail::SurvivalPredictor{model, 1e-6}(snapshot, origin, t).seen))
          << t.transpose();
      ASSERT_EQ(detail::UnblockedPredictor{&map.free_space()}(map, origin, t).seen,
                detail::UnblockedPredictor{}(map, origin, t).seen)
          << t.transpose();
      seen += cells.seen > 0.0;
    }
  }
  EXPECT_GT(seen, 100);
}

TEST(FreeSpace, TheSweptEstimateCrossesCubesToRounding) {
  const OccupancyGrid grid = cluttered();
  const ClassMap map(grid);
  std::vector<Frustum> views;
  for (int k = 0; k < 8; ++k) {
    const double yaw = 0.8 * k;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(0.6 * std::cos(yaw), 0.6 * std::sin(yaw), 0.1);
    pose.linear() = Eigen::AngleAxisd(yaw + 3.14159, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    views.emplace_back(pose, SensorFov{deg2rad(57), deg2rad(43), 0.1, 1.5});
  }
  for (const GainQuantity rule : {GainQuantity::kSurvivalCells, GainQuantity::kCount}) {
    SweptConfig config;
    config.alpha = 0.9;
    const std::vector<double> cubes = swept_view_counts(map, views, rule, config);
    config.skip_free = false;
    const std::vector<double> cells = swept_view_counts(map, views, rule, config);
    for (std::size_t v = 0; v < views.size(); ++v) {
      EXPECT_GT(cells[v], 1.0);
      EXPECT_NEAR(cubes[v], cells[v], 1e-9 * cells[v]) << "view " << v;
    }
  }
}

TEST(ClassMap, ReadsTheSnapshotsClassesNestsItsSamplesAndListsASampleAsTheBox) {
  const OccupancyGrid grid = cluttered();
  const GainMap snapshot(grid, 1);
  const ClassMap classes(grid);
  std::vector<std::uint32_t> unobserved;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    ASSERT_EQ(classes.state(i), snapshot.value(i).state) << i;
    if (grid.state(i) == CellState::kUnobserved)
      unobserved.push_back(static_cast<std::uint32_t>(i));
  }
  // The race's samples: list b the sample of b bits, list k < b those of k bits but not k + 1.
  const std::vector<std::vector<std::uint32_t>> levels = unobserved_by_sample(classes, 64);
  const int b = static_cast<int>(levels.size()) - 1;
  ASSERT_GT(b, 0);
  EXPECT_EQ(levels.back(), unobserved_sample(classes, b));
  for (int k = 0; k < b; ++k) {
    std::vector<std::uint32_t> band;
    for (const std::uint32_t i : unobserved) {
      if (in_cell_sample(i, k) && !in_cell_sample(i, k + 1)) band.push_back(i);
    }
    EXPECT_EQ(levels[static_cast<std::size_t>(k)], band) << k;
  }
  // Lists on a sample of every unobserved cell are the lists of each view's box walk.
  std::vector<Frustum> views;
  for (const Eigen::Vector3d& origin :
       {Eigen::Vector3d(-0.6, 0.0, 0.1), Eigen::Vector3d(0.05, 0.01, 0.02)}) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = origin;
    views.emplace_back(pose, SensorFov{deg2rad(57), deg2rad(43), 0.05, 1.5});
  }
  for (const GainMethod method : {GainMethod::kSurvival, GainMethod::kGreedy}) {
    GainConfig config;
    config.method = method;
    config.alpha = 0.9;
    config.num_threads = 1;
    const std::vector<ViewCells> a = exact_view_cells(classes, views, config, unobserved);
    const std::vector<ViewCells> box = exact_view_cells(classes, views, config);
    ASSERT_EQ(a.size(), box.size());
    for (std::size_t v = 0; v < a.size(); ++v) {
      EXPECT_GT(a[v].cells.size(), 50u);
      EXPECT_EQ(a[v].cells, box[v].cells);
      EXPECT_EQ(a[v].seen, box[v].seen);
      EXPECT_EQ(a[v].targets, box[v].targets);
    }
  }
}

}  // namespace
}  // namespace vantage
