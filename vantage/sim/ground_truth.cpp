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

/// NOTE: cells are shrunk by this fraction of their size before overlap tests, so that a surface
/// lying exactly on a cell face (up to rounding) overlaps neither neighbour.
constexpr double kShrink = 1e-6;

/// Whether a triangle overlaps the box of centre c and half sizes h (separating axis test,
/// Akenine-Möller 2001: box axes, triangle normal, and the 9 edge-axis cross products).
bool triangle_overlaps_box(const Eigen::Vector3d& c, const Eigen::Vector3d& h,
                           const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& d) {
  const std::array<Eigen::Vector3d, 3> v = {a - c, b - c, d - c};
  for (int i = 0; i < 3; ++i) {
    const double lo = std::min({v[0][i], v[1][i], v[2][i]});
    const double hi = std::max({v[0][i], v[1][i], v[2][i]});
    if (lo > h[i] || hi < -h[i]) return false;
  }
  const std::array<Eigen::Vector3d, 3> e = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  const Eigen::Vector3d normal = e[0].cross(e[1]);
  if (std::abs(normal.dot(v[0])) > h.dot(normal.cwiseAbs())) return false;
  for (const Eigen::Vector3d& edge : e) {
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d axis = Eigen::Vector3d::Unit(i).cross(edge);
      const double p0 = axis.dot(v[0]), p1 = axis.dot(v[1]), p2 = axis.dot(v[2]);
      const double r = h.dot(axis.cwiseAbs());
      if (std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r) return false;
    }
  }
  return true;
}

/// Whether the segment from p to p + d meets the triangle (a, b, c), edges and ends included
/// (Möller–Trumbore with a small tolerance). A segment parallel to the triangle's plane does not.
bool segment_meets_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& d,
                            const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c) {
  constexpr double kEps = 1e-9;
  const Eigen::Vector3d e1 = b - a, e2 = c - a;
  const Eigen::Vector3d h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) <= 1e-12 * d.norm() * e1.norm() * e2.norm()) return false;
  const double f = 1.0 / det;
  const Eigen::Vector3d s = p - a;
  const double u = f * s.dot(h);
  if (u < -kEps || u > 1.0 + kEps) return false;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = f * d.dot(q);
  if (v < -kEps || u + v > 1.0 + kEps) return false;
  const double t = f * e2.dot(q);
  return t >= -kEps && t <= 1.0 + kEps;
}

/// Linear indices of the grid cells a closed mesh occupies: the cells its surface crosses, and
/// the cells the outside cannot reach. The outside floods from cell centre to neighbouring cell
/// centre wherever the segment between them meets no triangle, so that a face lying exactly on
/// cell boundaries still walls the inside off.
std::vector<std::uint32_t> voxelize_mesh(const TriangleMesh& mesh, const GridSpec& grid) {
  const Eigen::AlignedBox3d box = mesh.bounds();
  const Index3 lo_full = grid.lattice_index(box.min()) - Index3::Ones();
  const Index3 hi_full = grid.lattice_index(box.max()) + Index3::Ones();
  // NOTE: the local box is clipped to the grid plus one cell. Its unclipped faces lie outside the
  // solid and seed the outside; clipped faces may cut through the solid, so they seed nothing.
  const Index3 lo = lo_full.cwiseMax(Index3::Constant(-1));
  const Index3 hi = hi_full.cwiseMin(grid.dims);
  if ((hi.array() < lo.array()).any()) return {};
  const Index3 size = hi - lo + Index3::Ones();
  const auto local = [&](const Index3& c) {
    const Index3 l = c - lo;
    return static_cast<std::size_t>(l.x()) +
           static_cast<std::size_t>(size.x()) *
               (static_cast<std::size_t>(l.y()) +
                static_cast<std::size_t>(size.y()) * static_cast<std::size_t>(l.z()));
  };
  const std::size_t count = static_cast<std::size_t>(size.x()) * size.y() * size.z();
  // Per local cell: bit 0-2 the segment to the +x/+y/+z neighbour's centre meets the surface,
  // bit 3 the surface crosses the cell, bit 4 the outside reached it.
  constexpr std::uint8_t kCrossed = 1 << 3, kOutside = 1 << 4;
  std::vector<std::uint8_t> flags(count, 0);

  const Eigen::Vector3d half = Eigen::Vector3d::Constant(grid.resolution * (0.5 - kShrink));
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Eigen::Vector3d& d = mesh.vertices[static_cast<std::size_t>(t[2])];
    const Eigen::Vector3d t_min = a.cwiseMin(b).cwiseMin(d), t_max = a.cwiseMax(b).cwiseMax(d);
    // Cells whose box or whose outgoing segments the triangle may touch.
    const Index3 c_lo = (grid.lattice_index(t_min) - Index3::Ones()).cwiseMax(lo);
    const Index3 c_hi = grid.lattice_index(t_max).cwiseMin(hi);
    for (int z = c_lo.z(); z <= c_hi.z(); ++z) {
      for (int y = c_lo.y(); y <= c_hi.y(); ++y) {
        for (int x = c_lo.x(); x <= c_hi.x(); ++x) {
          const Index3 cell(x, y, z);
          std::uint8_t& f = flags[local(cell)];
          const Eigen::Vector3d center = grid.center(cell);
          if ((f & kCrossed) == 0 && triangle_overlaps_box(center, half, a, b, d)) f |= kCrossed;
          for (int axis = 0; axis < 3; ++axis) {
            const auto bit = static_cast<std::uint8_t>(1 << axis);
            if ((f & bit) != 0 || cell[axis] == hi[axis]) continue;
            if (segment_meets_triangle(center, Eigen::Vector3d::Unit(axis) * grid.resolution, a, b,
                                       d)) {
              f |= bit;
            }
          }
        }
      }
    }
  }

  // Flood the outside from the unclipped faces of the local box.
  std::deque<Index3> queue;
  auto reach = [&](const Index3& c) {
    std::uint8_t& f = flags[local(c)];
    if ((f & kOutside) != 0) return;
    f |= kOutside;
    queue.push_back(c);
  };
  for (int axis = 0; axis < 3; ++axis) {
    for (const bool upper : {false, true}) {
      const bool clipped = upper ? hi[axis] != hi_full[axis] : lo[axis] != lo_full[axis];
      if (clipped) continue;
      const int fixed = upper ? hi[axis] : lo[axis];
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      for (int i = lo[u]; i <= hi[u]; ++i) {
        for (int j = lo[w]; j <= hi[w]; ++j) {
          Index3 c;
          c[axis] = fixed;
          c[u] = i;
          c[w] = j;
          reach(c);
        }
      }
    }
  }
  while (!queue.empty()) {
    const Index3 c = queue.front();
    queue.pop_front();
    for (int axis = 0; axis < 3; ++axis) {
      const auto bit = static_cast<std::uint8_t>(1 << axis);
      if (c[axis] < hi[axis] && (flags[local(c)] & bit) == 0) {
        Index3 n = c;
        ++n[axis];
        reach(n);
      }
      if (c[axis] > lo[axis]) {
        Index3 n = c;
        --n[axis];
        if ((flags[local(n)] & bit) == 0) reach(n);
      }
    }
  }

  std::vector<std::uint32_t> cells;
  for (int z = std::max(lo.z(), 0); z <= std::min(hi.z(), grid.dims.z() - 1); ++z) {
    for (int y = std::max(lo.y(), 0); y <= std::min(hi.y(), grid.dims.y() - 1); ++y) {
      for (int x = std::max(lo.x(), 0); x <= std::min(hi.x(), grid.dims.x() - 1); ++x) {
        const Index3 cell(x, y, z);
        const std::uint8_t f = flags[local(cell)];
        if ((f & kCrossed) != 0 || (f & kOutside) == 0) {
          cells.push_back(static_cast<std::uint32_t>(grid.linear(cell)));
        }
      }
    }
  }
  return cells;
}

/// Linear indices of the grid cells whose interior overlaps a sphere.
std::vector<std::uint32_t> voxelize_sphere(const Sphere& sphere, const GridSpec& grid) {
  const Eigen::Vector3d r = Eigen::Vector3d::Constant(sphere.radius);
  const Index3 lo = grid.lattice_index(sphere.center - r).cwiseMax(Index3::Zero());
  const Index3 hi = grid.lattice_index(sphere.center + r).cwiseMin(grid.dims - Index3::Ones());
  const double half = grid.resolution * (0.5 - kShrink);
  std::vector<std::uint32_t> cells;
  for (int z = lo.z(); z <= hi.z(); ++z) {
    for (int y = lo.y(); y <= hi.y(); ++y) {
      for (int x = lo.x(); x <= hi.x(); ++x) {
        const Index3 cell(x, y, z);
        const Eigen::Vector3d c = grid.center(cell);
        // Distance from the sphere's centre to the nearest point of the (shrunk) cell.
        const Eigen::Vector3d gap =
            ((sphere.center - c).cwiseAbs() - Eigen::Vector3d::Constant(half)).cwiseMax(0.0);
        if (gap.squaredNorm() < sphere.radius * sphere.radius) {
          cells.push_back(static_cast<std::uint32_t>(grid.linear(cell)));
        }
      }
    }
  }
  return cells;
}

bool overlaps_grid(const Eigen::AlignedBox3d& box, const GridSpec& grid) {
  const double eps = grid.resolution * kShrink;
  return (box.min().array() < grid.max_corner().array() - eps).all() &&
         (box.max().array() > grid.origin.array() + eps).all();
}

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

std::vector<std::uint8_t> voxelize(const std::vector<Shape>& shapes, const GridSpec& grid,
                                   int num_threads) {
  grid.validate();
  if (grid.num_cells() > std::size_t{1} << 32) {
    throw std::invalid_argument("voxelize: the grid has more cells than 32-bit indices hold");
  }
  std::vector<std::vector<std::uint32_t>> per_shape(shapes.size());
  run_with_threads(num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, shapes.size(), [&](std::size_t i) {
      const Shape& shape = shapes[i];
      if (!overlaps_grid(shape.bounds(), grid)) return;
      per_shape[i] = shape.sphere ? voxelize_sphere(*shape.sphere, grid)
                                  : voxelize_mesh(shape.mesh_world, grid);
    });
  });
  std::vector<std::uint8_t> occupied(grid.num_cells(), 0);
  for (const auto& cells : per_shape) {
    for (const std::uint32_t c : cells) occupied[c] = 1;
  }
  return occupied;
}

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

std::vector<Eigen::Vector2d> reachable_stops(const Scene& scene,
                                             const std::vector<std::uint8_t>& occupied) {
  const GridSpec& grid = scene.grid;
  if (occupied.size() != grid.num_cells()) {
    throw std::invalid_argument("reachable_stops: occupancy does not match the scene's grid");
  }
  // Columns that hold an obstacle below the robot's height.
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
  const double radius = scene.robot.footprint / 2;
  auto clear = [&](const Eigen::Vector2d& p) {
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
  };

  const double spacing = scene.robot.stop_spacing;
  const Eigen::AlignedBox2d& area = scene.floor_area;
  const int sx = std::max(1, static_cast<int>(std::floor(area.sizes().x() / spacing)));
  const int sy = std::max(1, static_cast<int>(std::floor(area.sizes().y() / spacing)));
  auto position = [&](int i, int j) {
    return Eigen::Vector2d(area.min().x() + (i + 0.5) * spacing,
                           area.min().y() + (j + 0.5) * spacing);
  };
  std::vector<std::uint8_t> state(static_cast<std::size_t>(sx) * sy, 0);  // 1 clear, 2 reached
  for (int j = 0; j < sy; ++j) {
    for (int i = 0; i < sx; ++i)
      state[static_cast<std::size_t>(j) * sx + i] = clear(position(i, j));
  }
  std::deque<std::pair<int, int>> queue;
  for (std::size_t k = 0; k < scene.start_poses.size(); ++k) {
    const Eigen::Vector2d p = scene.start_poses[k].translation().head<2>();
    if (!clear(p)) {
      throw std::invalid_argument(cat(scene.name, ": start_poses[", k, "] at (", p.x(), ", ", p.y(),
                                      ") is not clear for a robot of footprint ",
                                      scene.robot.footprint, " m"));
    }
    bool seeded = false;
    for (int j = 0; j < sy; ++j) {
      for (int i = 0; i < sx; ++i) {
        std::uint8_t& s = state[static_cast<std::size_t>(j) * sx + i];
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
      throw std::invalid_argument(cat(scene.name, ": start_poses[", k, "] at (", p.x(), ", ", p.y(),
                                      ") has no clear stop within ", spacing, " m"));
    }
  }
  while (!queue.empty()) {
    const auto [i, j] = queue.front();
    queue.pop_front();
    constexpr std::array<std::array<int, 2>, 4> kSteps = {{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};
    for (const auto& [di, dj] : kSteps) {
      const int a = i + di, b = j + dj;
      if (a < 0 || b < 0 || a >= sx || b >= sy) continue;
      std::uint8_t& s = state[static_cast<std::size_t>(b) * sx + a];
      if (s != 1) continue;
      s = 2;
      queue.emplace_back(a, b);
    }
  }
  std::vector<Eigen::Vector2d> stops;
  for (int j = 0; j < sy; ++j) {
    for (int i = 0; i < sx; ++i) {
      if (state[static_cast<std::size_t>(j) * sx + i] == 2) stops.push_back(position(i, j));
    }
  }
  return stops;
}

std::vector<Viewpoint> ground_truth_viewpoints(const World& world,
                                               const std::vector<std::uint8_t>& occupied,
                                               std::span<const Eigen::Isometry3d> views) {
  const Scene& scene = world.scene();
  std::vector<Viewpoint> viewpoints;
  if (scene.kind == SceneKind::kTableTop) {
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
