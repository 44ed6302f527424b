// The occupied cells' shadows (vantage/gain/octant_shadows.hpp): their bits against the
// recurrence solved cell by cell, and a cell they hide against the walks that would reach it,
// from origins outside and inside the grid.

#include "vantage/gain/octant_shadows.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "vantage/map/occupancy_grid.hpp"
#include "vantage/map/traversal.hpp"

namespace vantage {
namespace {

/// A 1.4 x 0.6 x 0.5 m grid of 2 cm cells (70 cells along x: two words a row), unobserved, with
/// hollow boxes of occupied cells (a few with a hole in a wall), occupied specks and free slabs
/// (fixed seed).
OccupancyGrid shells() {
  GridSpec spec;
  spec.origin = {-0.7, -0.3, -0.25};
  spec.resolution = 0.02;
  spec.dims = {70, 30, 25};
  OccupancyGrid grid(spec);
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> x(0, 60), y(0, 22), z(0, 18), size(3, 9);
  for (int k = 0; k < 9; ++k) {
    const Index3 lo(x(rng), y(rng), z(rng));
    const Index3 hi =
        (lo + Index3(size(rng), size(rng), size(rng))).cwiseMin(spec.dims - Index3::Ones());
    for (int c = lo.z(); c <= hi.z(); ++c) {
      for (int b = lo.y(); b <= hi.y(); ++b) {
        for (int a = lo.x(); a <= hi.x(); ++a) {
          const bool wall = a == lo.x() || a == hi.x() || b == lo.y() || b == hi.y() ||
                            c == lo.z() || c == hi.z();
          const bool hole = k % 3 == 0 && c == hi.z() && a == (lo.x() + hi.x()) / 2;
          if (wall && !hole) grid.set_probability(spec.linear({a, b, c}), 0.9);
        }
      }
    }
  }
  std::uniform_int_distribution<int> any_x(0, 69), any_y(0, 29), any_z(0, 24);
  for (int k = 0; k < 300; ++k) {
    grid.set_probability(spec.linear({any_x(rng), any_y(rng), any_z(rng)}), 0.9);
  }
  for (int k = 0; k < 4000; ++k) {
    const std::size_t i = spec.linear({any_x(rng), any_y(rng), any_z(rng)});
    if (grid.state(i) == CellState::kUnobserved) grid.set_probability(i, 0.1);
  }
  return grid;
}

TEST(OctantShadows, BitsAreTheRecurrenceSolvedCellByCell) {
  const OccupancyGrid grid = shells();
  const GridSpec& spec = grid.spec();
  const OctantShadows shadows(spec, grid.classes(), grid.census(), 2);
  std::size_t set = 0;
  for (int o = 0; o < 8; ++o) {
    const Index3 step((o & 1) ? 1 : -1, (o & 2) ? 1 : -1, (o & 4) ? 1 : -1);
    // OB per cell, in an order that visits every cell's predecessors first.
    std::vector<char> ob(grid.size(), 0), b(grid.size(), 0);
    for (int kz = 0; kz < spec.dims.z(); ++kz) {
      for (int ky = 0; ky < spec.dims.y(); ++ky) {
        for (int kx = 0; kx < spec.dims.x(); ++kx) {
          const Index3 c(step.x() > 0 ? kx : spec.dims.x() - 1 - kx,
                         step.y() > 0 ? ky : spec.dims.y() - 1 - ky,
                         step.z() > 0 ? kz : spec.dims.z() - 1 - kz);
          bool blocked = true;
          for (int a = 0; a < 3; ++a) {
            Index3 p = c;
            p[a] -= step[a];
            blocked = blocked && spec.contains(p) && ob[spec.linear(p)];
          }
          const std::size_t i = spec.linear(c);
          b[i] = blocked;
          ob[i] = blocked || grid.state(i) == CellState::kOccupied;
        }
      }
    }
    for (std::size_t i = 0; i < grid.size(); ++i) {
      const bool expected = ob[i] != 0;
      ASSERT_EQ(((shadows.bits(spec.unravel(i)) >> o) & 1) != 0, expected)
          << "octant " << o << ", cell " << spec.unravel(i).transpose();
      if (b[i] && grid.state(i) != CellState::kOccupied) ++set;
    }
  }
  EXPECT_GT(set, 5000u);  // the boxes' insides, and more
}

/// Whether the walk from `from` to `to` enters the cell `target` before any occupied cell, as
/// every walk of the project stops on its first occupied cell.
bool reaches(const OccupancyGrid& grid, const Eigen::Vector3d& from, const Eigen::Vector3d& to,
             const Index3& target) {
  const GridSpec& spec = grid.spec();
  GridWalk walk(spec, from, to);
  if (!walk.entered()) return false;
  for (;;) {
    if (walk.cell() == target) return true;
    if (grid.state(walk.linear()) == CellState::kOccupied) return false;
    if (walk.at_end()) return false;
    walk.advance();
    if (walk.ends_outside() && !spec.contains(walk.cell())) return false;
  }
}

TEST(OctantShadows, NoWalkReachesACellTheyHide) {
  const OccupancyGrid grid = shells();
  const GridSpec& spec = grid.spec();
  const OctantShadows shadows(spec, grid.classes(), grid.census(), 1);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d lo = spec.origin, size = spec.max_corner() - spec.origin;
  std::size_t hidden = 0, walks = 0;
  for (int k = 0; k < 60; ++k) {
    // Origins around the grid and inside it; inside, on a free cell or an unobserved one.
    const double spread = k % 3 == 0 ? 1.0 : 2.0;
    Eigen::Vector3d origin;
    for (int a = 0; a < 3; ++a) origin[a] = lo[a] + size[a] * (0.5 + spread * (unit(rng) - 0.5));
    if (k % 5 == 0) origin = {-0.7 - 0.3 * unit(rng), 0.02, 0.01};  // in a cell's slabs
    const std::uint8_t open = shadows.open_octants(origin);
    for (std::size_t i = 0; i < grid.size(); i += 7) {
      const Index3 c = spec.unravel(i);
      if (grid.state(i) == CellState::kOccupied || !shadows.hides(origin, open, c)) continue;
      ++hidden;
      // Walks to the centre, the corners and random points of the cell's cube.
      const Eigen::Vector3d corner = spec.origin + c.cast<double>() * spec.resolution;
      std::vector<Eigen::Vector3d> points{spec.center(c)};
      for (int q = 0; q < 8; ++q) {
        points.push_back(corner + spec.resolution * Eigen::Vector3d(q & 1, (q >> 1) & 1, q >> 2));
      }
      for (int q = 0; q < 4; ++q) {
        points.push_back(corner +
                         spec.resolution * Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
      }
      for (const Eigen::Vector3d& p : points) {
        // Past the point too, as a sensor's ray runs on to its range.
        for (const double past : {1.0, 1.7}) {
          ++walks;
          ASSERT_FALSE(reaches(grid, origin, origin + past * (p - origin), c))
              << "origin " << origin.transpose() << ", cell " << c.transpose();
        }
      }
    }
  }
  EXPECT_GT(hidden, 5000u);
  EXPECT_GT(walks, 150000u);
}

// The cells a race samples (OctantShadows::reachable): in their order, the same on one thread
// and two, and every cell left out hidden from every origin (hides); the cells span many runs.
TEST(OctantShadows, ReachableLeavesOutOnlyCellsHiddenFromEveryOrigin) {
  const OccupancyGrid grid = shells();
  const GridSpec& spec = grid.spec();
  const OctantShadows shadows(spec, grid.classes(), grid.census(), 2);
  std::vector<std::uint32_t> cells;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (grid.state(i) != CellState::kOccupied) cells.push_back(static_cast<std::uint32_t>(i));
  }
  ASSERT_GT(cells.size(), 3u * 4096u);
  const std::vector<Eigen::Vector3d> origins = {{-1.5, 0.1, 0.2}, {-1.3, -0.3, 0.4}};
  const std::vector<std::uint32_t> kept = shadows.reachable(origins, cells, 1);
  EXPECT_EQ(shadows.reachable(origins, cells, 2), kept);
  ASSERT_LT(kept.size(), cells.size());  // the shells hide some from both
  std::size_t k = 0;
  for (const std::uint32_t i : cells) {
    if (k < kept.size() && kept[k] == i) {
      ++k;
      continue;
    }
    for (const Eigen::Vector3d& o : origins) {
      ASSERT_TRUE(shadows.hides(o, shadows.open_octants(o), spec.unravel(i)))
          << "cell " << i << " left out, origin " << o.transpose();
    }
  }
  EXPECT_EQ(k, kept.size());  // the kept cells in their order
}

}  // namespace
}  // namespace vantage
