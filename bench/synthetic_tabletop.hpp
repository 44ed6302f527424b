#pragma once
/// @file
/// A synthetic table top for the oracle tests and the benchmarks: boxes and cylinders on a 1 m
/// table, an analytic pinhole ray caster, and map states after a few paper-mode scans from the
/// ring. It needs the core only, so tests and benchmarks run before and without vantage::sim.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "vantage/map/integrate.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/views/ring.hpp"

namespace vantage::synthetic {

/// A box, rotated by `yaw` about world z.
struct Box {
  Eigen::Vector3d center;  ///< [m]
  Eigen::Vector3d half;    ///< half extents [m]
  double yaw = 0.0;        ///< [rad]
};

/// An upright cylinder.
struct Cylinder {
  Eigen::Vector2d center;  ///< [m]
  double radius;           ///< [m]
  double z0, z1;           ///< bottom and top [m]
};

/// Everything a ray can hit.
struct Scene {
  std::vector<Box> boxes;
  std::vector<Cylinder> cylinders;
};

inline constexpr double kResolution = 1.0 / 128.0;  ///< the paper's table-top cell [m]
/// The table's top; the middle of the grid's bottom layer, so its points fall in that layer.
inline constexpr double kTableTop = -0.5 * kResolution;

/// A table-top grid of `cells` x `cells` x 65 cells at 1/128 m, centred on the world origin in x
/// and y, its bottom layer holding the table's top. Cell bounds lie on multiples of the
/// resolution, as OctoMap's keys do, so the same map can be loaded into an octomap::OcTree.
inline GridSpec grid_spec(int cells = 129) {
  GridSpec spec;
  spec.resolution = kResolution;
  spec.dims = Index3(cells, cells, 65);
  const double half = std::floor(cells / 2.0) * kResolution;
  spec.origin = Eigen::Vector3d(-half, -half, -kResolution);
  return spec;
}

/// The table (`scale` m square), the floor, and a layout of objects repeated on a
/// `scale` x `scale` lattice of 1 m tiles. `layout` 0 is moderately cluttered, 1 is dense.
inline Scene table_top(int layout = 0, int scale = 1) {
  Scene scene;
  const double half_table = 0.5 * scale;
  scene.boxes.push_back(
      {{0, 0, -0.375 + kTableTop / 2}, {half_table, half_table, 0.375 + kTableTop / 2}, 0});
  scene.boxes.push_back({{0, 0, -0.77}, {20, 20, 0.02}, 0});  // floor
  std::vector<Box> boxes;
  std::vector<Cylinder> cylinders;
  if (layout == 0) {
    boxes = {{{0.10, 0.05, 0.075}, {0.06, 0.04, 0.075}, 0.35},
             {{-0.20, 0.20, 0.05}, {0.10, 0.05, 0.05}, -0.17},
             {{0.30, 0.30, 0.125}, {0.03, 0.03, 0.125}, 0.0},
             {{-0.30, -0.05, 0.04}, {0.05, 0.075, 0.04}, 0.6}};
    cylinders = {{{0.25, -0.20}, 0.04, 0.0, 0.20},
                 {{-0.10, -0.25}, 0.06, 0.0, 0.12},
                 {{0.00, 0.30}, 0.03, 0.0, 0.18}};
  } else {
    boxes = {{{0.00, 0.00, 0.10}, {0.05, 0.05, 0.10}, 0.2},
             {{0.12, 0.02, 0.06}, {0.04, 0.06, 0.06}, -0.3},
             {{-0.10, 0.08, 0.08}, {0.06, 0.03, 0.08}, 0.8},
             {{0.05, -0.14, 0.05}, {0.08, 0.04, 0.05}, 0.1},
             {{-0.15, -0.10, 0.14}, {0.03, 0.03, 0.14}, 0.0},
             {{0.25, 0.22, 0.03}, {0.10, 0.10, 0.03}, 0.4},
             {{-0.28, 0.28, 0.09}, {0.04, 0.09, 0.09}, -0.5}};
    cylinders = {{{0.18, 0.14}, 0.035, 0.0, 0.22},
                 {{-0.05, 0.20}, 0.05, 0.0, 0.15},
                 {{0.22, -0.25}, 0.06, 0.0, 0.10},
                 {{-0.30, -0.30}, 0.04, 0.0, 0.25},
                 {{-0.25, 0.02}, 0.03, 0.0, 0.20}};
  }
  for (int i = 0; i < scale; ++i) {
    for (int j = 0; j < scale; ++j) {
      const Eigen::Vector3d shift(i - (scale - 1) / 2.0, j - (scale - 1) / 2.0, 0.0);
      for (Box b : boxes) {
        b.center += shift;
        scene.boxes.push_back(b);
      }
      for (Cylinder c : cylinders) {
        c.center += shift.head<2>();
        scene.cylinders.push_back(c);
      }
    }
  }
  return scene;
}

/// Distance along a unit ray to the first surface, or infinity.
inline double cast(const Scene& scene, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  double best = std::numeric_limits<double>::infinity();
  for (const Box& b : scene.boxes) {
    const double c = std::cos(b.yaw), s = std::sin(b.yaw);
    const Eigen::Vector3d ro = o - b.center;
    const Eigen::Vector3d lo(c * ro.x() + s * ro.y(), -s * ro.x() + c * ro.y(), ro.z());
    const Eigen::Vector3d ld(c * d.x() + s * d.y(), -s * d.x() + c * d.y(), d.z());
    double t0 = 0.0, t1 = best;
    bool hit = true;
    for (int a = 0; a < 3 && hit; ++a) {
      if (std::abs(ld[a]) < 1e-15) {
        hit = std::abs(lo[a]) <= b.half[a];
        continue;
      }
      double ta = (-b.half[a] - lo[a]) / ld[a], tb = (b.half[a] - lo[a]) / ld[a];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
      hit = t0 <= t1;
    }
    if (hit && t0 > 0.0) best = std::min(best, t0);
  }
  for (const Cylinder& cy : scene.cylinders) {
    const Eigen::Vector2d p = o.head<2>() - cy.center;
    const Eigen::Vector2d q = d.head<2>();
    const double a = q.squaredNorm(), b = p.dot(q), c = p.squaredNorm() - cy.radius * cy.radius;
    if (a > 1e-15) {  // the side
      const double disc = b * b - a * c;
      if (disc >= 0.0) {
        const double t = (-b - std::sqrt(disc)) / a;
        const double z = o.z() + t * d.z();
        if (t > 0.0 && z >= cy.z0 && z <= cy.z1) best = std::min(best, t);
      }
    }
    if (std::abs(d.z()) > 1e-15) {  // the caps
      for (const double z : {cy.z0, cy.z1}) {
        const double t = (z - o.z()) / d.z();
        if (t > 0.0 && (p + t * q).squaredNorm() <= cy.radius * cy.radius) best = std::min(best, t);
      }
    }
  }
  return best;
}

/// A pinhole depth image of `width` x `height` pixels over the view's field of view, as world
/// points; rays without a hit in [min_range, max_range] give no point.
inline PointCloud scan(const Scene& scene, const Frustum& view, int width, int height) {
  PointCloud points;
  points.reserve(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  const SensorFov& fov = view.fov();
  const double tan_h = std::tan(fov.h_fov / 2), tan_v = std::tan(fov.v_fov / 2);
  const Eigen::Matrix3d R = view.T_world_sensor().linear();
  const Eigen::Vector3d o = view.origin();
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      const double u = tan_h * (1.0 - 2.0 * (c + 0.5) / width);
      const double v = tan_v * (1.0 - 2.0 * (r + 0.5) / height);
      const Eigen::Vector3d d = (R * Eigen::Vector3d(1.0, u, v)).normalized();
      const double t = cast(scene, o, d);
      if (t >= fov.min_range && t <= fov.max_range) points.push_back(o + t * d);
    }
  }
  return points;
}

/// The ring the tests and benchmarks use: 10 positions x 3 yaw offsets around the table, the
/// sensor 0.6 m above it (times `scale` for tiled tables).
inline std::vector<Frustum> ring_views(int scale = 1, int positions = 10) {
  RingConfig ring;
  ring.center = Eigen::Vector3d(0, 0, 0.1);
  ring.radius = 1.0 * scale;
  ring.height = 0.6 * scale;
  ring.positions = positions;
  return make_views(ring_poses(ring), SensorFov{});
}

/// Ring indices scanned, in order, to build the map states (yaw offset 0 at spread positions).
inline constexpr int kScanOrder[] = {1, 16, 7, 22, 10, 25, 4, 19};

/// The map after the first `scans` scans of kScanOrder, each `width` x `height`, integrated in
/// `mode` (paper by default).
inline OccupancyGrid map_after(const Scene& scene, const GridSpec& spec, int scans, int width = 320,
                               int height = 240, IntegrationMode mode = IntegrationMode::kPaper,
                               int scale = 1) {
  OccupancyGrid grid(spec);
  const std::vector<Frustum> views = ring_views(scale);
  IntegrationConfig config;
  config.mode = mode;
  for (int k = 0; k < scans; ++k) {
    const Frustum& view = views[static_cast<std::size_t>(kScanOrder[k])];
    integrate_scan(grid, Scan{scan(scene, view, width, height), view}, config);
  }
  return grid;
}

}  // namespace vantage::synthetic
