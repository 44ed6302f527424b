#pragma once
/// @file
/// The field's yardstick for a table top (issue 36): surface coverage by scan points, counted
/// against the object surface that the scene's candidate views and starts hit together, and the
/// true hit set of every candidate that the greedy oracle and the set-cover bound work from.
///
/// Definitions (docs/yardstick.md):
/// - object surface S: the surface cells (sim::surface_cells) of the scene's shapes other than
///   the table and the floor, voxelized alone (sim::voxelize). The table's own surface does not
///   count: the mapper segments it away, so no run measures it.
/// - covered: a cell c of S is covered by a point p, at a tolerance of t cells (0 or 1), when
///   p's cell lies within t cells of c along every axis: at t = 1 (the default, issue 36) c or
///   one of its 26 neighbours, i.e. p within one resolution of c's box (L-infinity); at t = 0
///   (issue 37, GenNBV's scanned voxels) p inside c itself.
/// - hit set of a view: the cells of S covered by the points of its noise-free scan (the scene's
///   sensor with its range noise set to zero, from the true pose) that lie on no table or floor
///   (outside their bounding boxes), as a run's segmented points do.
/// - visible surface V (the denominator): the union of the hit sets of the candidate set and the
///   starts, each scanned once.
/// - surface coverage = |covered cells of V| / |V|; raw surface coverage = |covered cells of S| /
///   |S|. The measured points are the registered object points the mapper integrated.

#include <Eigen/Geometry>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vantage/map/grid_spec.hpp"
#include "vantage/map/point_cloud.hpp"
#include "vantage/sim/world.hpp"

namespace vantage {

/// Shape kinds that carry the objects rather than being them: not part of the object surface.
inline constexpr std::string_view kSupportKinds[] = {"table", "floor"};

/// The object surface S of a scene in its grid, ascending linear indices (see the file comment).
std::vector<std::uint32_t> object_surface_cells(const sim::Scene& scene, int num_threads = 0);

/// The tolerances the yardstick knows in cells (the file's note).
inline constexpr int kMaxCoverageTolerance = 1;

/// The largest tolerance a distance may give [m]: a metre is no scan point's error.
inline constexpr double kMaxCoverageToleranceMetres = 1.0;

/// When a point covers a cell: within `cells` cells (0: in it, MA-SCVP's; 1: in it or one of its
/// 26 neighbours, issue 36's), or, when `metres` > 0, within that distance of the cell's box
/// (PB-NBV counts a ground-truth point covered by a scan point within 5 mm).
struct CoverageTolerance {
  int cells = 1;        ///< 0 or 1 (kMaxCoverageTolerance), when metres is 0
  double metres = 0.0;  ///< > 0: Euclidean distance from the point to the cell's box [m]

  CoverageTolerance(int c = 1) : cells(c) {}  // NOLINT(google-explicit-constructor): cells
  /// Within `m` of the cell [m].
  static CoverageTolerance within(double m);
  bool operator==(const CoverageTolerance&) const = default;
  /// Throws std::invalid_argument naming the value.
  void validate() const;
  /// How a point covers a cell, in words ("in it", "within 5 mm of it", ...).
  std::string describe() const;
  /// "0", "1" (cells) or "5mm" (a distance).
  std::string label() const;
};

/// "0" or "1" [cells], or a distance with its unit, "5mm" or "0.005m"; throws
/// std::invalid_argument naming the text.
CoverageTolerance parse_coverage_tolerance(std::string_view text);

/// The cells of `cells` (ascending) that some point of `points_world` covers at `tolerance`: the
/// point's cell is the cell or, at 1 cell, one of its 26 neighbours, or the point lies within the
/// tolerance's distance of the cell's box. Points outside the grid count for the border cells
/// they lie next to. Ascending.
std::vector<std::uint32_t> covered_cells(const GridSpec& grid, std::span<const std::uint32_t> cells,
                                         const PointCloud& points_world,
                                         CoverageTolerance tolerance = 1);

/// The size of the intersection of two ascending index lists.
std::size_t count_common(std::span<const std::uint32_t> a, std::span<const std::uint32_t> b);

/// The ground truth the yardstick needs for one scene and candidate set.
struct SurfaceTruth {
  GridSpec grid;
  CoverageTolerance tolerance;         ///< when a point covers a cell (the file's note)
  std::vector<std::uint32_t> surface;  ///< S, ascending
  std::vector<std::uint32_t> visible;  ///< V: the cells of S some candidate or start hits
  /// Per candidate view, its hit set: the cells of S its noise-free scan covers (a subset of
  /// V), ascending.
  std::vector<std::vector<std::uint32_t>> candidate_hits;
  /// Per start pose of the scene, the same.
  std::vector<std::vector<std::uint32_t>> start_hits;
  double seconds = 0.0;  ///< wall time of the noise-free scans and their cells [s]
};

/// Scans the world noise-free from every candidate and every start pose of its scene, and
/// collects S, V and each one's hit set at `tolerance` cells. Deterministic for any thread count
/// (World::scan is).
SurfaceTruth compute_surface_truth(const sim::World& world,
                                   std::span<const Eigen::Isometry3d> candidates,
                                   CoverageTolerance tolerance,
                                   int num_threads = 0);

/// The surface coverage figures of a set of measured points.
struct SurfaceCoverage {
  double visible = 0.0;                ///< covered share of V, in [0, 1]
  double raw = 0.0;                    ///< covered share of S, in [0, 1]
  std::vector<std::uint32_t> covered;  ///< the covered cells of V, ascending
};

/// Surface coverage of `points_world` (registered measured points) against `truth`, at its
/// tolerance.
SurfaceCoverage surface_coverage(const SurfaceTruth& truth, const PointCloud& points_world);

}  // namespace vantage
