#pragma once
/// @file
/// Ground truth of a simulated world in the experiment's grid: which cells are truly occupied,
/// which of them form surfaces, and which surface cells a sensor can see from at least one
/// viewpoint (the denominator of a coverage figure that means something).

#include <Eigen/Geometry>
#include <cstdint>
#include <span>
#include <vector>

#include "vantage/map/grid_spec.hpp"
#include "vantage/sim/geometry.hpp"
#include "vantage/sim/scene.hpp"
#include "vantage/sim/world.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage::sim {

/// Marks each grid cell whose interior overlaps a solid (1) or not (0), by linear index.
///
/// A mesh is a solid: the cells its triangles cross, and the cells they enclose (found by a
/// flood fill of the outside through the cells no triangle crosses). Touching is not overlap: a
/// surface that lies exactly on a cell face (the table top under the table-top grid, the floor
/// under an office grid) occupies neither cell. A mesh with holes wider than a cell keeps only its
/// surface cells; a sphere is exact. Deterministic for any thread count.
std::vector<std::uint8_t> voxelize(const std::vector<Shape>& shapes, const GridSpec& grid,
                                   int num_threads = 0);

/// Occupied cells with at least one of their 26 neighbours not occupied (or outside the grid), as
/// ascending linear indices: every cell a surface can be seen in.
std::vector<std::uint32_t> surface_cells(const GridSpec& grid,
                                         const std::vector<std::uint8_t>& occupied);

/// A place the sensor can look from: one view, or the steps of a 360° sweep (same origin).
struct Viewpoint {
  std::vector<Frustum> frusta;
};

/// The cells of `cells` that some viewpoint sees: a ray from the viewpoint's origin, aimed at a
/// point of the surface inside the cell (up to 8, found by short probe rays across the cell),
/// whose first hit lies inside that cell and inside one of the viewpoint's frusta (field of view
/// and range). Ascending order. Deterministic for any thread count.
std::vector<std::uint32_t> observable_cells(const World& world, const GridSpec& grid,
                                            std::span<const std::uint32_t> cells,
                                            const std::vector<Viewpoint>& viewpoints,
                                            int num_threads = 0);

/// Floor stops (x, y) a robot of the scene's footprint can reach from any start: a lattice of
/// `robot.stop_spacing` over the floor area, each stop clear of occupied cells below
/// `robot.height` within half the footprint, connected to a start through clear neighbours.
/// Throws std::invalid_argument naming a start that is not clear.
std::vector<Eigen::Vector2d> reachable_stops(const Scene& scene,
                                             const std::vector<std::uint8_t>& occupied);

/// The viewpoints the ground truth counts: on a table top, the candidate views (`views`, or the
/// scene's ring when empty: an arm's hemisphere is the run's, not the scene's) and the starts; in
/// an office, a 360° sweep at every reachable stop.
std::vector<Viewpoint> ground_truth_viewpoints(const World& world,
                                               const std::vector<std::uint8_t>& occupied,
                                               std::span<const Eigen::Isometry3d> views = {});

/// Everything ground truth holds for one scene.
struct GroundTruth {
  GridSpec grid;
  std::vector<std::uint8_t> occupied;     ///< per linear index: 1 = truly occupied
  std::vector<std::uint32_t> surface;     ///< surface cells, ascending
  std::vector<std::uint32_t> observable;  ///< surface cells some viewpoint sees, ascending
  std::size_t occupied_count = 0;
  std::size_t viewpoints = 0;  ///< how many viewpoints `observable` was computed from
};

/// Voxelizes the world's scene in its grid, finds its surface cells and those observable from
/// ground_truth_viewpoints(world, occupied, views). Deterministic for any thread count.
GroundTruth compute_ground_truth(const World& world, int num_threads = 0,
                                 std::span<const Eigen::Isometry3d> views = {});

}  // namespace vantage::sim
