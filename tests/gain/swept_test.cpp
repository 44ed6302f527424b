// The swept estimate (vantage/gain/evaluators/swept.hpp) against what it estimates: the volume of
// an unobstructed frustum inside an unobserved grid (greedy's count of cells), nothing in free
// space or behind a wall, the survival reading below greedy on the same rays, and the same numbers
// for any thread count; and the bound on every estimate that proves views out.

#include "vantage/gain/evaluators/swept.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "vantage/gain/evaluators/hierarchy.hpp"

namespace vantage {
namespace {

/// A 2 m cube of 2 cm cells around the origin, all unobserved.
OccupancyGrid cube() {
  GridSpec spec;
  spec.origin = {-1.0, -1.0, -1.0};
  spec.resolution = 0.02;
  spec.dims = {100, 100, 100};
  return OccupancyGrid(spec);
}

/// A view from `origin` along +x, 50 x 40 degrees, 0.3-`range` m.
Frustum along_x(const Eigen::Vector3d& origin, double range) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = origin;
  return Frustum(pose, SensorFov{deg2rad(50), deg2rad(40), 0.3, range});
}

/// The volume of a pinhole frustum between the ranges r0 and r1 [m^3]: the solid angle of its
/// rectangle times (r1^3 - r0^3) / 3.
double frustum_volume(const SensorFov& fov, double r0, double r1) {
  const double a = std::tan(fov.h_fov / 2), b = std::tan(fov.v_fov / 2);
  const double omega = 4.0 * std::asin(a * b / std::sqrt((1 + a * a) * (1 + b * b)));
  return omega * (r1 * r1 * r1 - r0 * r0 * r0) / 3.0;
}

TEST(Swept, AnUnobstructedFrustumCountsItsVolumeInCells) {
  const OccupancyGrid grid = cube();
  const GainMap map(grid, 1);
  const Frustum view = along_x({-0.9, 0.0, 0.0}, 1.6);
  const std::vector<Frustum> views{view};
  const double cells = frustum_volume(view.fov(), 0.3, 1.6) / std::pow(0.02, 3);
  const double swept =
      swept_view_counts(ClassMap(grid), views, GainQuantity::kCount, SweptConfig{})[0];
  EXPECT_NEAR(swept, cells, 0.01 * cells);
  // ... and the exact count of the cells whose centres lie inside, to the boundary's share.
  GainConfig gain;
  gain.method = GainMethod::kGreedy;
  const double exact = count_view_gains(map, nullptr, views, GainQuantity::kCount, gain)[0].cells;
  EXPECT_NEAR(swept, exact, 0.02 * exact);
}

TEST(Swept, FreeSpaceAndTheSpaceBehindAWallCountNothing) {
  OccupancyGrid grid = cube();
  const Frustum view = along_x({-0.9, 0.0, 0.0}, 1.6);
  const std::vector<Frustum> views{view};
  for (std::size_t i = 0; i < grid.size(); ++i) grid.set_probability(i, 0.12);
  EXPECT_EQ(swept_view_counts(ClassMap(grid), views, GainQuantity::kCount, SweptConfig{})[0], 0.0);
  // Unobserved everywhere, an occupied wall at x = 0 across the whole view: only the space
  // between the sensor's near range and the wall counts.
  grid = cube();
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const Index3 c = grid.spec().unravel(i);
    if (c.x() == 50) grid.set_probability(i, 0.97);
  }
  const double swept =
      swept_view_counts(ClassMap(grid), views, GainQuantity::kCount, SweptConfig{})[0];
  EXPECT_GT(swept, 0.0);
  // Every ray stops on the wall, 0.9 m away along the axis and farther off it: at most the
  // frustum up to 0.9 m / cos of the corner's angle.
  const double a = std::tan(view.fov().h_fov / 2), b = std::tan(view.fov().v_fov / 2);
  const double corner = 0.9 * std::sqrt(1 + a * a + b * b);
  EXPECT_LE(swept, frustum_volume(view.fov(), 0.3, corner) / std::pow(0.02, 3));
  EXPECT_GE(swept, frustum_volume(view.fov(), 0.3, 0.88) / std::pow(0.02, 3));
}

TEST(Swept, SurvivalSeesLessThanGreedyAndOneThreadDecidesAsTwo) {
  OccupancyGrid grid = cube();
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const Eigen::Vector3d c = grid.spec().center(grid.spec().unravel(i));
    if (c.x() < -0.4) grid.set_probability(i, 0.12);  // free air before the sensor's target
    if ((c - Eigen::Vector3d(0.0, 0.1, 0.0)).norm() < 0.15) grid.set_probability(i, 0.97);
  }
  std::vector<Frustum> views;
  for (int k = 0; k < 6; ++k) {
    views.push_back(along_x({-0.9, -0.3 + 0.1 * k, 0.05 * k}, 2.0));
  }
  const ClassMap map(grid);
  SweptConfig config;
  config.num_threads = 1;
  const std::vector<double> greedy = swept_view_counts(map, views, GainQuantity::kCount, config);
  config.alpha = 0.99;
  const std::vector<double> survival =
      swept_view_counts(map, views, GainQuantity::kSurvivalCells, config);
  config.num_threads = 2;
  EXPECT_EQ(swept_view_counts(map, views, GainQuantity::kSurvivalCells, config), survival);
  for (std::size_t v = 0; v < views.size(); ++v) {
    EXPECT_GT(survival[v], 0.0) << v;
    EXPECT_LT(survival[v], greedy[v]) << v;
  }
  config.alpha = 1.0;  // a = 1 is greedy
  EXPECT_EQ(swept_view_counts(map, views, GainQuantity::kSurvivalCells, config), greedy);
}

// The bound the swept search proves candidates out by: every ray's credit at a visibility of 1
// all the way, so no estimate exceeds it, whatever the map; an unobstructed frustum inside an
// unobserved grid reaches it to the sums' rounding.
TEST(Swept, NoEstimateExceedsItsViewsBound) {
  OccupancyGrid grid = cube();
  std::vector<Frustum> views{along_x({-0.9, 0.0, 0.0}, 1.6), along_x({0.5, 0.0, 0.0}, 1.2)};
  SweptConfig config;
  const std::vector<double> bounds = swept_view_bounds(views, grid.spec().resolution, config);
  const std::vector<double> open =
      swept_view_counts(ClassMap(grid), views, GainQuantity::kCount, config);
  EXPECT_NEAR(open[0], bounds[0], 1e-8 * bounds[0]);
  EXPECT_LE(open[0], bounds[0]);
  EXPECT_LT(open[1], 0.5 * bounds[1]);  // most of it outside the grid, which is free
  // Random states (one cell in 200 occupied, 3 in 10 free), and views from inside and outside the
  // grid at several pitches.
  std::uint64_t state = 7;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const std::uint64_t pick = (state >> 33) % 1000;
    if (pick < 5) grid.set_probability(i, 0.97);
    if (pick >= 700) grid.set_probability(i, 0.12);
  }
  for (int k = 0; k < 4; ++k) views.push_back(along_x({-1.5 + 0.4 * k, 0.1 * k, -0.2}, 2.5));
  const ClassMap map(grid);
  for (const int rays : {1, 7, 32}) {
    config.rays_across = rays;
    const std::vector<double> bound = swept_view_bounds(views, grid.spec().resolution, config);
    for (const GainQuantity quantity : {GainQuantity::kCount, GainQuantity::kSurvivalCells}) {
      const std::vector<double> counts = swept_view_counts(map, views, quantity, config);
      for (std::size_t v = 0; v < views.size(); ++v) {
        EXPECT_GT(counts[v], 0.0) << v;
        EXPECT_LE(counts[v], bound[v]) << v << " at " << rays << " rays across";
      }
    }
  }
  EXPECT_THROW(swept_view_bounds(views, 0.0, config), std::invalid_argument);
}

TEST(Swept, RefusesRaysAcrossOutsideItsRange) {
  const OccupancyGrid grid = cube();
  const ClassMap map(grid);
  const std::vector<Frustum> views{along_x({-0.9, 0.0, 0.0}, 1.6)};
  SweptConfig config;
  config.rays_across = 0;
  EXPECT_THROW(swept_view_counts(map, views, GainQuantity::kCount, config), std::invalid_argument);
  config.rays_across = 32;
  config.alpha = 0.0;
  EXPECT_THROW(swept_view_counts(map, views, GainQuantity::kSurvivalCells, config),
               std::invalid_argument);
}

}  // namespace
}  // namespace vantage
