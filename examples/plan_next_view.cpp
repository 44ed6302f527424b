// Plans the next view of a box on a table from two scans, with an installed Vantage, and writes
// the map as an OctoMap file.
#include <cstdio>
#include <vantage/gain/evaluators/exact.hpp>
#include <vantage/io/octomap_io.hpp>
#include <vantage/map/integrate.hpp>
#include <vantage/planner/choose.hpp>
#include <vantage/views/ring.hpp>

using namespace vantage;

// A scan from `eye`: the box face |coordinate `axis`| = 0.1 that faces it, the box top and the
// table in front of that face (a synthetic stand-in for a depth camera's cloud).
Scan synthetic_scan(const Eigen::Vector3d& eye, int axis, const SensorFov& fov) {
  Scan scan{{}, Frustum(look_at(eye, {0, 0, 0.05}), fov)};
  const int other = 1 - axis;
  for (double u = -0.1; u <= 0.1; u += 0.01) {
    for (double v = 0.0; v <= 0.15; v += 0.01) {  // the face
      Eigen::Vector3d p(0, 0, v);
      p[axis] = 0.1, p[other] = u;
      scan.points_world.push_back(p);
    }
    for (double v = -0.1; v <= 0.1; v += 0.01) scan.points_world.emplace_back(u, v, 0.15);  // top
    for (double v = 0.1; v <= 0.38; v += 0.01) {  // the table in front of the face
      Eigen::Vector3d p(0, 0, 0.005);
      p[axis] = v, p[other] = 3 * u;
      scan.points_world.push_back(p);
    }
  }
  return scan;
}

int main() {
  GridSpec spec;  // 0.8 m x 0.8 m x 0.4 m over the table, 2 cm cells
  spec.origin = {-0.4, -0.4, 0.0};
  spec.resolution = 0.02;
  spec.dims = {40, 40, 20};
  OccupancyGrid grid(spec);
  const SensorFov fov{deg2rad(57.0), deg2rad(43.0), 0.3, 3.0};
  integrate_scan(grid, synthetic_scan({1.0, 0.0, 0.6}, 0, fov), {});
  integrate_scan(grid, synthetic_scan({0.0, 1.0, 0.6}, 1, fov), {});

  RingConfig ring;  // 10 positions x 3 yaw offsets around the box (the paper's table-top set)
  ring.center = {0, 0, 0.05};
  ring.height = 0.6;
  const std::vector<Frustum> views = make_views(ring_poses(ring), fov);
  const std::vector<ViewGain> gains = exact_view_gains(grid, views, GainConfig{});
  std::vector<double> bits;
  for (const ViewGain& g : gains) bits.push_back(g.gain);
  const std::size_t best = choose_best(bits);
  const Eigen::Vector3d at = views[best].origin();
  std::printf("unobserved cells: %zu of %zu\n", grid.counts().unobserved, grid.size());
  std::printf("best view %zu of %zu at (%.3f, %.3f, %.3f): expected gain %.1f bits\n", best,
              views.size(), at.x(), at.y(), at.z(), bits[best]);
  write_octomap("map.bt", grid);  // the map for octovis
}
