// Exact traversal against a brute-force oracle: the slab intersection of the segment with every
// cell of the grid.

#include "vantage/map/traversal.hpp"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <vector>

namespace vantage {
namespace {

struct Visit {
  Index3 cell;
  std::size_t linear;
  int m;
};

std::vector<Visit> walk(const GridSpec& spec, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                        TraversalResult* result = nullptr) {
  std::vector<Visit> visits;
  const TraversalResult r = traverse(spec, a, b, [&](const Index3& c, std::size_t l, int m) {
    visits.push_back({c, l, m});
  });
  if (result != nullptr) *result = r;
  return visits;
}

/// Length of the part of segment a-b inside the closed cell, or -1 when they do not meet.
/// The cell is inflated by `slack` on every side, to absorb rounding at exact corner crossings.
double overlap(const GridSpec& spec, const Index3& cell, const Eigen::Vector3d& a,
               const Eigen::Vector3d& b, double slack = 0.0) {
  const Eigen::Vector3d lo =
      spec.origin + cell.cast<double>() * spec.resolution - Eigen::Vector3d::Constant(slack);
  const Eigen::Vector3d hi = lo + Eigen::Vector3d::Constant(spec.resolution + 2.0 * slack);
  const Eigen::Vector3d d = b - a;
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-300) {
      if (a[k] < lo[k] || a[k] > hi[k]) return -1.0;
      continue;
    }
    double u = (lo[k] - a[k]) / d[k], v = (hi[k] - a[k]) / d[k];
    if (u > v) std::swap(u, v);
    t0 = std::max(t0, u);
    t1 = std::min(t1, v);
  }
  return t1 < t0 ? -1.0 : (t1 - t0) * d.norm();
}

/// Checks one segment against the oracle; returns a description of the first failure.
::testing::AssertionResult agrees_with_oracle(const GridSpec& spec, const Eigen::Vector3d& a,
                                              const Eigen::Vector3d& b) {
  TraversalResult result;
  const std::vector<Visit> visits = walk(spec, a, b, &result);
  const double tol = 1e-9 * spec.resolution;
  std::set<std::size_t> seen;
  for (std::size_t i = 0; i < visits.size(); ++i) {
    const Visit& v = visits[i];
    if (!spec.contains(v.cell)) return ::testing::AssertionFailure() << "visited outside the grid";
    if (v.linear != spec.linear(v.cell)) return ::testing::AssertionFailure() << "wrong linear";
    if (!seen.insert(v.linear).second) return ::testing::AssertionFailure() << "repeated a cell";
    if (overlap(spec, v.cell, a, b, tol) < -0.5) {
      return ::testing::AssertionFailure() << "visited a cell the segment does not touch";
    }
    if (i > 0) {
      if ((v.cell - visits[i - 1].cell).cwiseAbs().sum() != 1) {
        return ::testing::AssertionFailure() << "consecutive cells do not share a face";
      }
      if (v.m != visits[i - 1].m + 1) return ::testing::AssertionFailure() << "m not consecutive";
    }
  }
  // Every cell the segment passes through with positive length is visited.
  const Index3 lo = spec.lattice_index(a.cwiseMin(b)).cwiseMax(Index3::Zero());
  const Index3 hi = spec.lattice_index(a.cwiseMax(b)).cwiseMin(spec.dims - Index3::Ones());
  for (int z = lo.z(); z <= hi.z(); ++z) {
    for (int y = lo.y(); y <= hi.y(); ++y) {
      for (int x = lo.x(); x <= hi.x(); ++x) {
        const Index3 c(x, y, z);
        if (overlap(spec, c, a, b) > tol && !seen.count(spec.linear(c))) {
          return ::testing::AssertionFailure()
                 << "skipped cell (" << x << "," << y << "," << z << ")";
        }
      }
    }
  }
  // The skipped count is the number of lattice steps from the origin's cell to the entry cell.
  if (!visits.empty()) {
    const int expected = (visits.front().cell - spec.lattice_index(a)).cwiseAbs().sum();
    if (result.skipped != expected || visits.front().m != expected) {
      return ::testing::AssertionFailure()
             << "skipped " << result.skipped << ", expected " << expected;
    }
  }
  return ::testing::AssertionSuccess();
}

GridSpec test_grid() {
  GridSpec spec;
  spec.origin = {-0.4, -0.3, 0.1};
  spec.resolution = 0.1;
  spec.dims = {8, 6, 5};
  return spec;
}

TEST(Traversal, RandomSegmentsInsideMatchOracle) {
  const GridSpec spec = test_grid();
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto inside = [&] {
    return Eigen::Vector3d(spec.origin +
                           spec.size().cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng))));
  };
  for (int i = 0; i < 3000; ++i) {
    const Eigen::Vector3d a = inside(), b = inside();
    ASSERT_TRUE(agrees_with_oracle(spec, a, b)) << "segment " << i;
    TraversalResult r;
    const auto visits = walk(spec, a, b, &r);
    ASSERT_TRUE(r.reached_end);
    ASSERT_EQ(visits.back().cell, spec.lattice_index(b));
    ASSERT_EQ(visits.front().cell, spec.lattice_index(a));
  }
}

TEST(Traversal, RandomSegmentsFromOutsideMatchOracle) {
  const GridSpec spec = test_grid();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 2.0);
  int entered = 0;
  for (int i = 0; i < 3000; ++i) {
    const Eigen::Vector3d a =
        spec.origin + spec.size().cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng)));
    const Eigen::Vector3d b =
        spec.origin + spec.size().cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng)));
    ASSERT_TRUE(agrees_with_oracle(spec, a, b)) << "segment " << i;
    TraversalResult r;
    walk(spec, a, b, &r);
    entered += r.entered;
  }
  EXPECT_GT(entered, 500);  // the sample exercises the entry jump
}

TEST(Traversal, AxisAlignedRays) {
  const GridSpec spec = test_grid();
  const Eigen::Vector3d c = spec.center({3, 2, 1});
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {-1.0, 1.0}) {
      const Eigen::Vector3d b = c + sign * 2.0 * Eigen::Vector3d::Unit(axis);
      ASSERT_TRUE(agrees_with_oracle(spec, c, b));
      const auto visits = walk(spec, c, b);
      const int expected =
          sign > 0 ? spec.dims[axis] - Index3(3, 2, 1)[axis] : Index3(3, 2, 1)[axis] + 1;
      EXPECT_EQ(static_cast<int>(visits.size()), expected) << "axis " << axis;
    }
  }
}

TEST(Traversal, ThroughCornersAndEdges) {
  const GridSpec spec = test_grid();
  // Diagonals through lattice corners and along cell edges.
  const Eigen::Vector3d corner = spec.origin + Eigen::Vector3d(0.2, 0.2, 0.2);
  ASSERT_TRUE(agrees_with_oracle(spec, corner, corner + Eigen::Vector3d(0.3, 0.3, 0.3)));
  ASSERT_TRUE(agrees_with_oracle(spec, corner, corner + Eigen::Vector3d(0.3, -0.2, 0.0)));
  ASSERT_TRUE(agrees_with_oracle(spec, corner, corner + Eigen::Vector3d(0.0, 0.3, 0.2)));
  ASSERT_TRUE(
      agrees_with_oracle(spec, spec.origin, spec.max_corner() - Eigen::Vector3d::Constant(1e-12)));
  // Along an edge shared by four cells.
  const auto visits = walk(spec, corner, corner + Eigen::Vector3d(0.35, 0.0, 0.0));
  EXPECT_EQ(visits.size(), 4u);
}

TEST(Traversal, ZeroLengthVisitsOneCell) {
  const GridSpec spec = test_grid();
  const Eigen::Vector3d p = spec.center({2, 2, 2});
  TraversalResult r;
  const auto visits = walk(spec, p, p, &r);
  ASSERT_EQ(visits.size(), 1u);
  EXPECT_EQ(visits[0].cell, Index3(2, 2, 2));
  EXPECT_TRUE(r.reached_end);
  EXPECT_EQ(r.skipped, 0);
  // Outside the grid: nothing visited, one cell skipped.
  const Eigen::Vector3d q = spec.origin - Eigen::Vector3d::Constant(1.0);
  EXPECT_TRUE(walk(spec, q, q, &r).empty());
  EXPECT_FALSE(r.entered);
  EXPECT_EQ(r.skipped, 1);
}

TEST(Traversal, StartingOutsideCountsSkippedCellsWithoutVisiting) {
  const GridSpec spec = test_grid();
  // 1 m to the left of the grid along x, aimed at cell (3, 2, 1).
  const Eigen::Vector3d target = spec.center({3, 2, 1});
  const Eigen::Vector3d origin = target - Eigen::Vector3d(1.3, 0.0, 0.0);
  TraversalResult r;
  const auto visits = walk(spec, origin, target, &r);
  ASSERT_EQ(visits.size(), 4u);
  EXPECT_EQ(r.skipped, 10);  // lattice cells -10 … -1 along x
  EXPECT_EQ(visits.front().m, 10);
  EXPECT_EQ(visits.front().cell, Index3(0, 2, 1));
  EXPECT_TRUE(r.reached_end);
}

TEST(Traversal, MissingTheGridVisitsNothing) {
  const GridSpec spec = test_grid();
  const Eigen::Vector3d a = spec.origin + Eigen::Vector3d(-1.0, -1.0, 0.2);
  const Eigen::Vector3d b = spec.origin + Eigen::Vector3d(-0.5, 3.0, 0.2);
  TraversalResult r;
  EXPECT_TRUE(walk(spec, a, b, &r).empty());
  EXPECT_FALSE(r.entered);
  EXPECT_EQ(r.skipped, lattice_cells_between(spec.lattice_index(a), spec.lattice_index(b)));
}

TEST(Traversal, VisitorCanStopEarly) {
  const GridSpec spec = test_grid();
  int calls = 0;
  const TraversalResult r = traverse(spec, spec.center({0, 0, 0}), spec.center({7, 5, 4}),
                                     [&](const Index3&, std::size_t, int) { return ++calls < 3; });
  EXPECT_EQ(calls, 3);
  EXPECT_TRUE(r.stopped);
  EXPECT_FALSE(r.reached_end);
}

TEST(Traversal, LeavingTheGridEndsTheWalk) {
  const GridSpec spec = test_grid();
  TraversalResult r;
  const auto visits =
      walk(spec, spec.center({1, 1, 1}), spec.center({1, 1, 1}) + Eigen::Vector3d(5, 0, 0), &r);
  EXPECT_EQ(visits.size(), 7u);
  EXPECT_FALSE(r.reached_end);
}

// ---------------------------------------------------------------------------------------------
// GridWalk, the one walker: traverse() runs on it, so the oracle tests above cover its steps;
// these check its jump.

/// A 40 x 36 x 30 grid of 5 cm cells.
GridSpec box_grid() {
  GridSpec spec;
  spec.origin = {-1.0, -0.9, 0.0};
  spec.resolution = 0.05;
  spec.dims = {40, 36, 30};
  return spec;
}

TEST(GridWalk, LeavingABoxInOneStepIsWalkingOutOfIt) {
  const GridSpec spec = box_grid();
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> ix(0, 39), iy(0, 35), iz(0, 29), side(1, 6);
  int jumps = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    // Half the rays from cell centres, which run through edges and corners (ties between axes).
    const Index3 o(ix(rng), iy(rng), iz(rng));
    const Eigen::Vector3d from =
        trial % 2 == 0 ? spec.center(o)
                       : spec.center(o) + Eigen::Vector3d(0.013, -0.007, 0.004) * (trial % 7);
    const Index3 target(ix(rng), iy(rng), iz(rng));
    GridWalk walk(spec, from, target);
    if (!walk.entered()) continue;
    while (!walk.at_end()) {
      const Index3 lo = walk.cell() - Index3(side(rng) - 1, side(rng) - 1, side(rng) - 1);
      const Index3 hi = walk.cell() + Index3(side(rng) - 1, side(rng) - 1, side(rng) - 1);
      const bool holds_target =
          (target.array() >= lo.array()).all() && (target.array() <= hi.array()).all();
      if (holds_target) {
        walk.advance();
        continue;
      }
      GridWalk stepped = walk;
      int cells = 0;
      while ((stepped.cell().array() >= lo.array()).all() &&
             (stepped.cell().array() <= hi.array()).all()) {
        ++cells;
        stepped.advance();
      }
      ASSERT_EQ(walk.leave_box(lo, hi), cells) << "trial " << trial;
      ASSERT_EQ(walk.cell(), stepped.cell()) << "trial " << trial;
      ASSERT_EQ(walk.m(), stepped.m());
      ASSERT_EQ(walk.linear(), spec.linear(walk.cell()));
      ++jumps;
    }
  }
  EXPECT_GT(jumps, 10000);
}

TEST(GridWalk, ClipToGridFindsTheBoxOrRejectsAParallelMiss) {
  const GridSpec spec = test_grid();
  const Eigen::Vector3d o = spec.origin - Eigen::Vector3d(1.0, -0.1, -0.1);
  double s_in = 0.0, s_out = 10.0;
  ASSERT_TRUE(clip_to_grid(spec, o, Eigen::Vector3d::UnitX(), s_in, s_out));
  EXPECT_NEAR(s_in, 1.0, 1e-12);
  EXPECT_NEAR(s_out, 1.0 + spec.size().x(), 1e-12);
  // Parallel to x but below the box: no crossing at all.
  const Eigen::Vector3d below = spec.origin - Eigen::Vector3d(1.0, 0.0, 0.5);
  s_in = 0.0, s_out = 10.0;
  EXPECT_FALSE(clip_to_grid(spec, below, Eigen::Vector3d::UnitX(), s_in, s_out));
  // Aimed away: the interval is empty.
  s_in = 0.0, s_out = 10.0;
  ASSERT_TRUE(clip_to_grid(spec, o, -Eigen::Vector3d::UnitX(), s_in, s_out));
  EXPECT_GT(s_in, s_out);
}

}  // namespace
}  // namespace vantage
