// The ground truth's occupancy (ground_truth.hpp, voxelize): which cells each shape of the world
// covers, by the separating-axis test of a triangle against a cell and a cell-centre parity test
// for the inside of a closed mesh, or by distance for a sphere.

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <stdexcept>

#include "vantage/sim/ground_truth.hpp"
#include "vantage/util/parallel.hpp"

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

// Per local cell: bit 0-2 the segment to the +x/+y/+z neighbour's centre meets the surface,
// bit 3 the surface crosses the cell, bit 4 the outside reached it.
constexpr std::uint8_t kCrossed = 1 << 3, kOutside = 1 << 4;

/// The cells around a mesh, one cell beyond its bounds and clipped to the grid plus one cell,
/// with their flags.
struct LocalBox {
  LocalBox(const Eigen::AlignedBox3d& box, const GridSpec& grid)
      : lo_full(grid.lattice_index(box.min()) - Index3::Ones()),
        hi_full(grid.lattice_index(box.max()) + Index3::Ones()),
        lo(lo_full.cwiseMax(Index3::Constant(-1))),
        hi(hi_full.cwiseMin(grid.dims)),
        size(hi - lo + Index3::Ones()) {}

  bool empty() const { return (hi.array() < lo.array()).any(); }
  std::size_t local(const Index3& c) const {
    const Index3 l = c - lo;
    return static_cast<std::size_t>(l.x()) +
           static_cast<std::size_t>(size.x()) *
               (static_cast<std::size_t>(l.y()) +
                static_cast<std::size_t>(size.y()) * static_cast<std::size_t>(l.z()));
  }

  Index3 lo_full, hi_full;
  // NOTE: the local box is clipped to the grid plus one cell. Its unclipped faces lie outside the
  // solid and seed the outside; clipped faces may cut through the solid, so they seed nothing.
  Index3 lo, hi;
  Index3 size;
  std::vector<std::uint8_t> flags;
};

/// Flags the cells the mesh's surface crosses, and the segments between cell centres it meets.
void mark_surface(const TriangleMesh& mesh, const GridSpec& grid, LocalBox& box) {
  const Index3 lo = box.lo, hi = box.hi;
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
          std::uint8_t& f = box.flags[box.local(cell)];
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
}

/// Floods the outside from the unclipped faces of the local box, across every segment between
/// cell centres that meets no triangle.
void flood_outside(LocalBox& box) {
  const Index3 lo = box.lo, hi = box.hi;
  std::vector<std::uint8_t>& flags = box.flags;
  std::deque<Index3> queue;
  auto reach = [&](const Index3& c) {
    std::uint8_t& f = flags[box.local(c)];
    if ((f & kOutside) != 0) return;
    f |= kOutside;
    queue.push_back(c);
  };
  for (int axis = 0; axis < 3; ++axis) {
    for (const bool upper : {false, true}) {
      const bool clipped = upper ? hi[axis] != box.hi_full[axis] : lo[axis] != box.lo_full[axis];
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
      if (c[axis] < hi[axis] && (flags[box.local(c)] & bit) == 0) {
        Index3 n = c;
        ++n[axis];
        reach(n);
      }
      if (c[axis] > lo[axis]) {
        Index3 n = c;
        --n[axis];
        if ((flags[box.local(n)] & bit) == 0) reach(n);
      }
    }
  }
}

/// Linear indices of the grid cells a closed mesh occupies: the cells its surface crosses, and
/// the cells the outside cannot reach. The outside floods from cell centre to neighbouring cell
/// centre wherever the segment between them meets no triangle, so that a face lying exactly on
/// cell boundaries still walls the inside off.
std::vector<std::uint32_t> voxelize_mesh(const TriangleMesh& mesh, const GridSpec& grid) {
  LocalBox box(mesh.bounds(), grid);
  if (box.empty()) return {};
  box.flags.assign(static_cast<std::size_t>(box.size.x()) * box.size.y() * box.size.z(), 0);
  mark_surface(mesh, grid, box);
  flood_outside(box);
  const Index3 lo = box.lo, hi = box.hi;
  std::vector<std::uint32_t> cells;
  for (int z = std::max(lo.z(), 0); z <= std::min(hi.z(), grid.dims.z() - 1); ++z) {
    for (int y = std::max(lo.y(), 0); y <= std::min(hi.y(), grid.dims.y() - 1); ++y) {
      for (int x = std::max(lo.x(), 0); x <= std::min(hi.x(), grid.dims.x() - 1); ++x) {
        const Index3 cell(x, y, z);
        const std::uint8_t f = box.flags[box.local(cell)];
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

}  // namespace vantage::sim
