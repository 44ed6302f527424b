#include "vantage/sim/ground_truth.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <stdexcept>

#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage::sim {
namespace {

/// Up to kMaxProbePoints points of the surface inside a cell, found by short probe rays across
/// the cell along each axis, both ways, on a 3 x 3 lattice of lines. Probes start a hair outside
/// the cell so that a face lying on its boundary is found too.
constexpr std::size_t kMaxProbePoints = 4;

std::vector<Eigen::Vector3d> surface_points(const World& world, const GridSpec& grid,
                                            const Index3& cell) {
  std::vector<Eigen::Vector3d> points;
  const double res = grid.resolution;
  const Eigen::Vector3d lo = grid.origin + cell.cast<double>() * res;
  const double margin = 0.01 * res;
  constexpr double kLines[3] = {1.0 / 6.0, 0.5, 5.0 / 6.0};
  // NOTE: the centre line first, so that a cell's first points are its most typical ones.
  constexpr int kOrder[9][2] = {{1, 1}, {0, 0}, {2, 2}, {0, 2}, {2, 0},
                                {0, 1}, {1, 0}, {2, 1}, {1, 2}};
  for (const auto& [i, j] : kOrder) {
    for (int axis = 0; axis < 3; ++axis) {
      for (const int sign : {1, -1}) {
        const int u = (axis + 1) % 3, w = (axis + 2) % 3;
        Eigen::Vector3d origin;
        origin[u] = lo[u] + kLines[i] * res;
        origin[w] = lo[w] + kLines[j] * res;
        origin[axis] = sign > 0 ? lo[axis] - margin : lo[axis] + res + margin;
        const Eigen::Vector3d dir = Eigen::Vector3d::Unit(axis) * sign;
        const auto t = world.cast(origin, dir, res + 2 * margin);
        if (!t) continue;
        const Eigen::Vector3d p = origin + *t * dir;
        bool fresh = true;
        for (const Eigen::Vector3d& q : points) fresh = fresh && (q - p).norm() > 0.1 * res;
        if (fresh) points.push_back(p);
        if (points.size() == kMaxProbePoints) return points;
      }
    }
  }
  return points;
}

}  // namespace

std::vector<std::uint32_t> surface_cells(const GridSpec& grid,
                                         const std::vector<std::uint8_t>& occupied) {
  if (occupied.size() != grid.num_cells()) {
    throw std::invalid_argument(cat("surface_cells: ", occupied.size(), " flags for a grid of ",
                                    grid.num_cells(), " cells"));
  }
  const int nz = grid.dims.z();
  std::vector<std::vector<std::uint32_t>> per_slab(static_cast<std::size_t>(nz));
  tbb::parallel_for(0, nz, [&](int z) {
    auto& out = per_slab[static_cast<std::size_t>(z)];
    for (int y = 0; y < grid.dims.y(); ++y) {
      for (int x = 0; x < grid.dims.x(); ++x) {
        const Index3 cell(x, y, z);
        const std::size_t i = grid.linear(cell);
        if (occupied[i] == 0) continue;
        // NOTE: 26 neighbours, not 6: a slanted face crosses cells whose only free neighbours lie
        // diagonally, and a sensor sees them all the same.
        bool surface = false;
        for (int dz = -1; dz <= 1 && !surface; ++dz) {
          for (int dy = -1; dy <= 1 && !surface; ++dy) {
            for (int dx = -1; dx <= 1 && !surface; ++dx) {
              const Index3 n = cell + Index3(dx, dy, dz);
              surface = !grid.contains(n) || occupied[grid.linear(n)] == 0;
            }
          }
        }
        if (surface) out.push_back(static_cast<std::uint32_t>(i));
      }
    }
  });
  std::vector<std::uint32_t> cells;
  for (const auto& slab : per_slab) cells.insert(cells.end(), slab.begin(), slab.end());
  return cells;
}

std::vector<std::uint32_t> observable_cells(const World& world, const GridSpec& grid,
                                            std::span<const std::uint32_t> cells,
                                            const std::vector<Viewpoint>& viewpoints,
                                            int num_threads) {
  std::vector<Eigen::Vector3d> origins;
  std::vector<double> reach;
  for (const Viewpoint& v : viewpoints) {
    if (v.frusta.empty()) throw std::invalid_argument("observable_cells: a viewpoint has no view");
    origins.push_back(v.frusta.front().origin());
    double r = 0.0;
    for (const Frustum& f : v.frusta) {
      r = std::max(r, (f.origin() - origins.back()).norm() + f.fov().max_range);
    }
    reach.push_back(r + grid.resolution);
  }
  const double nudge = grid.resolution * 1e-4;
  // NOTE: the ray stops this short of p: far more than the float rounding of Embree's hits, far
  // less than any feature of a scene.
  const double clearance = grid.resolution * 1e-3;
  std::vector<std::uint8_t> seen(cells.size(), 0);

  // Whether one viewpoint sees surface point p of `cell`: p lies in one of its frusta and nothing
  // lies on the ray before p, so that the ray's first hit is p.
  auto sees = [&](const Viewpoint& v, const Index3& cell, const Eigen::Vector3d& p) {
    for (const Frustum& f : v.frusta) {
      if (!f.contains(p)) continue;
      const Eigen::Vector3d o = f.origin();
      const double distance = (p - o).norm();
      const Eigen::Vector3d dir = (p - o) / distance;
      // NOTE: a hit is nudged into the surface, so that a face lying exactly on a cell boundary
      // belongs to the solid's cell, as the voxelization has it.
      if (grid.lattice_index(p + nudge * dir) != cell) continue;
      if (!world.occluded(o, dir, distance - clearance)) return true;
    }
    return false;
  };

  run_with_threads(num_threads, [&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& block) {
                        std::vector<std::size_t> near;
                        for (std::size_t i = block.begin(); i != block.end(); ++i) {
                          const Index3 cell = grid.unravel(cells[i]);
                          const std::vector<Eigen::Vector3d> points =
                              surface_points(world, grid, cell);
                          if (points.empty()) continue;
                          const Eigen::Vector3d center = grid.center(cell);
                          near.clear();
                          for (std::size_t v = 0; v < viewpoints.size(); ++v) {
                            if ((origins[v] - center).squaredNorm() <= reach[v] * reach[v])
                              near.push_back(v);
                          }
                          // One point from every viewpoint first: it settles most cells with few
                          // rays.
                          bool found = false;
                          for (std::size_t s = 0; s < points.size() && !found; ++s) {
                            for (const std::size_t v : near) {
                              if ((found = sees(viewpoints[v], cell, points[s]))) break;
                            }
                          }
                          seen[i] = found ? 1 : 0;
                        }
                      });
  });
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (seen[i] != 0) out.push_back(cells[i]);
  }
  return out;
}

namespace {

/// Per column of the grid (x + nx * y), whether it holds an obstacle below the robot's height.
std::vector<std::uint8_t> blocked_columns(const Scene& scene,
                                          const std::vector<std::uint8_t>& occupied) {
  const GridSpec& grid = scene.grid;
  const int nx = grid.dims.x(), ny = grid.dims.y();
  std::vector<std::uint8_t> blocked(static_cast<std::size_t>(nx) * ny, 0);
  for (int z = 0; z < grid.dims.z(); ++z) {
    if (grid.origin.z() + z * grid.resolution >= scene.robot.height) break;
    for (int y = 0; y < ny; ++y) {
      for (int x = 0; x < nx; ++x) {
        if (occupied[grid.linear({x, y, z})] != 0)
          blocked[static_cast<std::size_t>(y) * nx + x] = 1;
      }
    }
  }
  return blocked;
}

/// Whether the robot's footprint, a disc, stands clear of every blocked column at a position.
struct Footprint {
  const GridSpec& grid;
  const std::vector<std::uint8_t>& blocked;  // blocked_columns
  double radius;

  bool clear(const Eigen::Vector2d& p) const {
    const int nx = grid.dims.x(), ny = grid.dims.y();
    const Eigen::Vector2d lo = grid.origin.head<2>(), hi = grid.max_corner().head<2>();
    if ((p.array() - radius < lo.array()).any() || (p.array() + radius > hi.array()).any()) {
      return false;
    }
    const int x0 = static_cast<int>(std::floor((p.x() - radius - lo.x()) / grid.resolution));
    const int x1 = static_cast<int>(std::floor((p.x() + radius - lo.x()) / grid.resolution));
    const int y0 = static_cast<int>(std::floor((p.y() - radius - lo.y()) / grid.resolution));
    const int y1 = static_cast<int>(std::floor((p.y() + radius - lo.y()) / grid.resolution));
    const double reach = radius + grid.resolution * std::sqrt(0.5);
    for (int y = std::max(y0, 0); y <= std::min(y1, ny - 1); ++y) {
      for (int x = std::max(x0, 0); x <= std::min(x1, nx - 1); ++x) {
        const Eigen::Vector2d c = lo + Eigen::Vector2d(x + 0.5, y + 0.5) * grid.resolution;
        if ((c - p).squaredNorm() <= reach * reach &&
            blocked[static_cast<std::size_t>(y) * nx + x] != 0) {
          return false;
        }
      }
    }
    return true;
  }
};

/// The floor's stops, `spacing` apart over its area, each marked 0 blocked, 1 clear or 2 reached.
struct StopLattice {
  StopLattice(const Eigen::AlignedBox2d& floor, double step, const Footprint& footprint)
      : area(floor),
        spacing(step),
        sx(std::max(1, static_cast<int>(std::floor(area.sizes().x() / spacing)))),
        sy(std::max(1, static_cast<int>(std::floor(area.sizes().y() / spacing)))),
        state(static_cast<std::size_t>(sx) * sy, 0) {
    for (int j = 0; j < sy; ++j) {
      for (int i = 0; i < sx; ++i) at(i, j) = footprint.clear(position(i, j));
    }
  }
  Eigen::Vector2d position(int i, int j) const {
    return Eigen::Vector2d(area.min().x() + (i + 0.5) * spacing,
                           area.min().y() + (j + 0.5) * spacing);
  }
  std::uint8_t& at(int i, int j) { return state[static_cast<std::size_t>(j) * sx + i]; }

  /// Marks reached every clear stop within a spacing of each start pose, queued to spread from.
  void seed(const Scene& scene, const Footprint& footprint) {
    for (std::size_t k = 0; k < scene.start_poses.size(); ++k) {
      const Eigen::Vector2d p = scene.start_poses[k].translation().head<2>();
      if (!footprint.clear(p)) {
        throw std::invalid_argument(cat(scene.name, ": start_poses[", k, "] at (", p.x(), ", ",
                                        p.y(), ") is not clear for a robot of footprint ",
                                        scene.robot.footprint, " m"));
      }
      bool seeded = false;
      for (int j = 0; j < sy; ++j) {
        for (int i = 0; i < sx; ++i) {
          std::uint8_t& s = at(i, j);
          if (s == 1 && (position(i, j) - p).norm() <= spacing) {
            s = 2;
            queue.emplace_back(i, j);
            seeded = true;
          } else if (s == 2 && (position(i, j) - p).norm() <= spacing) {
            seeded = true;
          }
        }
      }
      if (!seeded) {
        throw std::invalid_argument(cat(scene.name, ": start_poses[", k, "] at (", p.x(), ", ",
                                        p.y(), ") has no clear stop within ", spacing, " m"));
      }
    }
  }

  /// Spreads from the queued stops to every clear stop four-connected to them.
  void spread() {
    while (!queue.empty()) {
      const auto [i, j] = queue.front();
      queue.pop_front();
      constexpr std::array<std::array<int, 2>, 4> kSteps = {{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};
      for (const auto& [di, dj] : kSteps) {
        const int a = i + di, b = j + dj;
        if (a < 0 || b < 0 || a >= sx || b >= sy) continue;
        std::uint8_t& s = at(a, b);
        if (s != 1) continue;
        s = 2;
        queue.emplace_back(a, b);
      }
    }
  }

  const Eigen::AlignedBox2d& area;
  double spacing;
  int sx, sy;
  std::vector<std::uint8_t> state;
  std::deque<std::pair<int, int>> queue;
};

}  // namespace

std::vector<Eigen::Vector2d> reachable_stops(const Scene& scene,
                                             const std::vector<std::uint8_t>& occupied) {
  const GridSpec& grid = scene.grid;
  if (occupied.size() != grid.num_cells()) {
    throw std::invalid_argument("reachable_stops: occupancy does not match the scene's grid");
  }
  const std::vector<std::uint8_t> blocked = blocked_columns(scene, occupied);
  const Footprint footprint{grid, blocked, scene.robot.footprint / 2};
  StopLattice lattice(scene.floor_area, scene.robot.stop_spacing, footprint);
  lattice.seed(scene, footprint);
  lattice.spread();
  std::vector<Eigen::Vector2d> stops;
  for (int j = 0; j < lattice.sy; ++j) {
    for (int i = 0; i < lattice.sx; ++i) {
      if (lattice.at(i, j) == 2) stops.push_back(lattice.position(i, j));
    }
  }
  return stops;
}

std::vector<Viewpoint> ground_truth_viewpoints(const World& world,
                                               const std::vector<std::uint8_t>& occupied,
                                               std::span<const Eigen::Isometry3d> views) {
  const Scene& scene = world.scene();
  std::vector<Viewpoint> viewpoints;
  if (scene.kind != SceneKind::kOffice) {
    const std::vector<Eigen::Isometry3d> ring =
        views.empty() ? scene.candidate_poses() : std::vector<Eigen::Isometry3d>{};
    for (const Eigen::Isometry3d& pose : views.empty() ? std::span(ring) : views) {
      viewpoints.push_back({{Frustum(pose, scene.fov())}});
    }
    for (const Eigen::Isometry3d& pose : scene.start_poses) {
      viewpoints.push_back({{Frustum(pose, scene.fov())}});
    }
    return viewpoints;
  }
  for (const Eigen::Vector2d& stop : reachable_stops(scene, occupied)) {
    Viewpoint v;
    for (const Eigen::Isometry3d& pose :
         world.sweep_poses(scene.mount.sensor_pose(stop.x(), stop.y())))
      v.frusta.emplace_back(pose, scene.fov());
    viewpoints.push_back(std::move(v));
  }
  return viewpoints;
}

GroundTruth compute_ground_truth(const World& world, int num_threads,
                                 std::span<const Eigen::Isometry3d> views) {
  const Scene& scene = world.scene();
  GroundTruth gt;
  gt.grid = scene.grid;
  gt.occupied = voxelize(scene.shapes, scene.grid, num_threads);
  gt.occupied_count =
      static_cast<std::size_t>(std::count(gt.occupied.begin(), gt.occupied.end(), 1));
  gt.surface = surface_cells(scene.grid, gt.occupied);
  const std::vector<Viewpoint> viewpoints = ground_truth_viewpoints(world, gt.occupied, views);
  gt.viewpoints = viewpoints.size();
  gt.observable = observable_cells(world, scene.grid, gt.surface, viewpoints, num_threads);
  return gt;
}

}  // namespace vantage::sim
