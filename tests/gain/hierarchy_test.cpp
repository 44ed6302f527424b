// The hierarchical walk and the bounds (vantage/gain/evaluators/hierarchy.hpp, bounds.hpp) against
// their references: block-crossing counts against cell-by-cell ones and the exact evaluation, bit
// for bit, and the upper bounds against every view's exact value. The walker's jump itself:
// tests/map/traversal_test.cpp.

#include "vantage/gain/evaluators/hierarchy.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "vantage/gain/evaluators/bounds.hpp"
#include "vantage/gain/evaluators/exact.hpp"

namespace vantage {
namespace {

/// A 40 x 36 x 30 grid of 5 cm cells: free air around a point, occupied boxes, a few cells at
/// odd probabilities, unobserved elsewhere; fixed seed.
OccupancyGrid cluttered_grid() {
  GridSpec spec;
  spec.origin = {-1.0, -0.9, 0.0};
  spec.resolution = 0.05;
  spec.dims = {40, 36, 30};
  OccupancyGrid grid(spec);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const Eigen::Vector3d c = spec.center(spec.unravel(i));
    if ((c - Eigen::Vector3d(-0.4, 0.0, 1.0)).norm() < 0.7) grid.set_probability(i, 0.12);
    if (c.z() < 0.3 && std::abs(c.x() - 0.3) < 0.2 && std::abs(c.y()) < 0.3) {
      grid.set_probability(i, 0.97);
    }
    if (c.x() > 0.6 && c.z() < 0.2) grid.set_probability(i, 0.12);  // a free slab to cross
    // A closed occupied shell, unobserved inside: no ray reaches in.
    const double shell = (c - Eigen::Vector3d(0.5, -0.5, 0.9)).cwiseAbs().maxCoeff();
    if (shell > 0.1 && shell < 0.2) grid.set_probability(i, 0.97);
    const double r = u(rng);
    if (c.x() < 0.0 && r < 0.01) grid.set_probability(i, 0.97);  // clutter on one side only
    if (c.x() < 0.0 && r > 0.99) grid.set_probability(i, 0.45);
  }
  return grid;
}

/// A view from `origin` looking at `target`, 60 x 45 degrees, 0.1-4 m.
Frustum view_at(const Eigen::Vector3d& origin, const Eigen::Vector3d& target) {
  const Eigen::Vector3d x = (target - origin).normalized();
  Eigen::Vector3d y = Eigen::Vector3d::UnitZ().cross(x);
  if (y.norm() < 1e-6) y = Eigen::Vector3d::UnitY();
  y.normalize();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear().col(0) = x;
  pose.linear().col(1) = y;
  pose.linear().col(2) = x.cross(y);
  pose.translation() = origin;
  return Frustum(pose, SensorFov{deg2rad(60), deg2rad(45), 0.1, 4.0});
}

/// Views around the grid: from outside, from inside free air, from cell centres (rays through
/// edges and corners), and one from inside unobserved space.
std::vector<Frustum> test_views(const GridSpec& spec) {
  std::vector<Frustum> views;
  const Eigen::Vector3d look(0.0, 0.0, 0.5);
  for (int k = 0; k < 8; ++k) {
    const double a = 0.8 * k;
    views.push_back(view_at({1.6 * std::cos(a), 1.6 * std::sin(a), 1.3 + 0.1 * k}, look));
  }
  views.push_back(view_at({-0.4, 0.0, 1.0}, look));          // in free air
  views.push_back(view_at(spec.center({5, 18, 20}), look));  // a cell centre
  views.push_back(view_at(spec.center({5, 18, 20}), spec.center({35, 18, 5})));
  views.push_back(view_at(spec.center({30, 30, 25}), look));  // unobserved space
  return views;
}

TEST(Hierarchy, BlockCrossingCountsAreTheCellByCellOnesAndTheExactOnes) {
  const OccupancyGrid grid = cluttered_grid();
  const GainMap map(grid, 1);
  const std::vector<Frustum> views = test_views(grid.spec());
  const ClassBlocks blocks = summarize_classes(map, views, 1);
  for (const double alpha : {0.9, 0.995, 1.0}) {
    for (const double epsilon : {0.0, 0.3}) {
      GainConfig config;
      config.alpha = alpha;
      config.epsilon = epsilon;
      config.num_threads = 2;
      config.method = GainMethod::kSurvival;
      const auto walked =
          count_view_gains(map, &blocks, views, GainQuantity::kSurvivalCells, config);
      const auto stepped =
          count_view_gains(map, nullptr, views, GainQuantity::kSurvivalCells, config);
      const auto exact = exact_view_gains(map, views, config);
      for (std::size_t v = 0; v < views.size(); ++v) {
        EXPECT_EQ(walked[v].cells, stepped[v].cells) << "view " << v << " a " << alpha;
        EXPECT_EQ(walked[v].cells, exact[v].cells) << "view " << v << " a " << alpha;
        EXPECT_EQ(walked[v].targets, exact[v].targets);
      }
    }
  }
  GainConfig greedy;
  greedy.method = GainMethod::kGreedy;
  const auto walked = count_view_gains(map, &blocks, views, GainQuantity::kCount, greedy);
  const auto stepped = count_view_gains(map, nullptr, views, GainQuantity::kCount, greedy);
  const auto exact = exact_view_gains(map, views, greedy);
  double total = 0.0;
  for (std::size_t v = 0; v < views.size(); ++v) {
    EXPECT_EQ(walked[v].gain, stepped[v].gain) << "view " << v;
    EXPECT_EQ(walked[v].gain, exact[v].gain) << "view " << v;
    total += walked[v].gain;
  }
  EXPECT_GT(total, 1000.0);  // the views do see something
}

TEST(Hierarchy, BoundsHoldForEveryView) {
  const OccupancyGrid grid = cluttered_grid();
  const GainMap map(grid, 1);
  const std::vector<Frustum> views = test_views(grid.spec());
  const ClassBlocks blocks = summarize_classes(map, views, 1);
  for (const double alpha : {0.9, 0.99, 0.995, 0.999, 1.0}) {
    GainConfig config;
    config.alpha = alpha;
    config.epsilon = 0.0;
    config.method = GainMethod::kSurvival;
    const auto exact = exact_view_gains(map, views, config);
    const auto cells =
        view_upper_bounds(blocks, grid.spec(), map, views, GainQuantity::kSurvivalCells, alpha);
    const auto bits =
        view_upper_bounds(blocks, grid.spec(), map, views, GainQuantity::kPaperBits, alpha);
    const auto open_bits =
        view_upper_bounds(blocks, grid.spec(), map, views, GainQuantity::kSurvivalBits, alpha);
    const auto all_cells =
        view_upper_bounds(blocks, grid.spec(), map, views, GainQuantity::kPaperCells, alpha);
    config.method = GainMethod::kProbabilistic;
    const auto paper = exact_view_gains(map, views, config);
    for (std::size_t v = 0; v < views.size(); ++v) {
      EXPECT_GE(cells[v], exact[v].cells) << "view " << v << " a " << alpha;
      EXPECT_GE(open_bits[v], exact[v].gain) << "view " << v << " a " << alpha;
      EXPECT_GE(bits[v], paper[v].gain) << "view " << v << " a " << alpha;
      EXPECT_GE(all_cells[v], paper[v].cells) << "view " << v << " a " << alpha;
    }
  }
  GainConfig greedy;
  greedy.method = GainMethod::kGreedy;
  const auto exact = exact_view_gains(map, views, greedy);
  const auto counts = view_upper_bounds(blocks, grid.spec(), map, views, GainQuantity::kCount, 1.0);
  for (std::size_t v = 0; v < views.size(); ++v) EXPECT_GE(counts[v], exact[v].gain);
}

TEST(Hierarchy, CellsInsideAClosedShellCannotBeReached) {
  const OccupancyGrid grid = cluttered_grid();
  const GridSpec& spec = grid.spec();
  const GainMap map(grid, 1);
  const std::vector<Frustum> views = test_views(spec);
  const ClassBlocks blocks = summarize_classes(map, views, 1);
  const std::size_t inside = spec.linear(spec.lattice_index({0.5, -0.5, 0.9}));
  EXPECT_FALSE(blocks.is_reachable(inside));
  EXPECT_TRUE(blocks.is_reachable(spec.linear(spec.lattice_index({0.5, -0.5, 1.2}))));
  // Brute force: no view's ray reaches an unreachable cell without an occupied cell on it.
  GainConfig greedy;
  greedy.method = GainMethod::kGreedy;
  std::size_t unreachable = 0;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (blocks.is_reachable(i) || grid.state(i) == CellState::kOccupied) continue;
    ++unreachable;
    for (const Frustum& view : views) {
      EXPECT_EQ(exact_cell_gain(grid, view.origin(), spec.unravel(i), greedy), 0.0);
    }
  }
  EXPECT_GT(unreachable, 50u);
}

TEST(Hierarchy, DepthIsTheOctantDistanceToAKnownBlock) {
  // Brute force over every block and octant, on a grid of whole and cut blocks, unobserved but
  // for a few free cells.
  GridSpec spec;
  spec.resolution = 0.1;
  spec.dims = {ClassBlocks::kBlock * 9, ClassBlocks::kBlock * 7 + 3, ClassBlocks::kBlock * 6};
  OccupancyGrid grid(spec);
  for (const Index3& c : {Index3(10, 10, 10), Index3(40, 20, 30), Index3(60, 50, 5)}) {
    grid.set_probability(spec.linear(c), 0.12);
  }
  const GainMap map(grid, 1);
  const ClassBlocks blocks = summarize_classes(map, test_views(grid.spec()), 2);
  const Index3 d = blocks.dims;
  const auto known = [&](const Index3& b) {
    if ((b.array() < 0).any() || (b.array() >= d.array()).any()) return true;
    const bool whole = ((b.array() + 1) * ClassBlocks::kBlock <= grid.spec().dims.array()).all();
    return blocks.classes[blocks.at(b)] != ClassBlocks::kHasUnobserved || !whole;
  };
  int deep = 0;
  for (int o = 0; o < 8; ++o) {
    const Index3 s((o & 1) ? 1 : -1, (o & 2) ? 1 : -1, (o & 4) ? 1 : -1);
    for (int z = 0; z < d.z(); ++z) {
      for (int y = 0; y < d.y(); ++y) {
        for (int x = 0; x < d.x(); ++x) {
          const Index3 b(x, y, z);
          int best = 0;
          if (!known(b)) {
            for (int r = 1; r < 64 && best == 0; ++r) {
              for (int k = 0; k < (r + 1) * (r + 1) * (r + 1) && best == 0; ++k) {
                const Index3 off(k % (r + 1), (k / (r + 1)) % (r + 1), k / ((r + 1) * (r + 1)));
                if (off.maxCoeff() == r && known(b + off.cwiseProduct(s))) best = r;
              }
            }
          }
          ASSERT_EQ(blocks.depth[o][blocks.at(b)], best) << "octant " << o;
          deep += best > 1 ? 1 : 0;
        }
      }
    }
  }
  EXPECT_GT(deep, 0);
}

}  // namespace
}  // namespace vantage
