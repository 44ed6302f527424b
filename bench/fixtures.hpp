#pragma once
/// @file
/// The map states and candidate views the benchmarks share, built once per process.

#include <vector>

#include "bench/synthetic_tabletop.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage::bench {

/// A map state and the views to evaluate on it.
struct World {
  OccupancyGrid grid;
  std::vector<Frustum> views;
  PointCloud last_scan;  ///< the points of the last scan, world frame [m]
  Frustum last_view;     ///< the view it was taken from
};

/// The 129 x 129 x 65 table top (1/128 m cells) after one 640 x 480 scan integrated in paper mode,
/// and the 30 ring candidates.
const World& table_top_after_one_scan();

/// A `cells` x `cells` x 65 grid at 1/128 m over a table tiled (cells - 1) / 128 times in x and
/// y, after one 640 x 480 scan integrated in endpoint mode (paper mode's unknown-space estimation
/// takes minutes on the largest grid), and the 300 candidates of candidates().
const World& scaled_world(int cells);

/// `n` candidates on the ring around a table tiled `scale` times: ceil(n / 3) positions x yaw
/// offsets {-15, 0, 15} degrees, the first n.
std::vector<Frustum> candidates(int n, int scale);

}  // namespace vantage::bench
