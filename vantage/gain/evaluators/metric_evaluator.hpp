#pragma once
/// @file
/// The field's volumetric information-gain metrics (Delmerico, Isler, Sabzevari & Scaramuzza,
/// "A comparison of volumetric information gain metrics for active 3D object reconstruction",
/// Autonomous Robots 42, 2018; docs/model.md "The field's metrics"): occlusion aware, unobserved
/// voxel, rear side voxel, rear side entropy, proximity count, Kriegel's average entropy and
/// Vasquez-Gomez's area factor, each a GainMethod behind `evaluate_views`.
///
/// Every metric is a sum (or, for two, a ratio) over the cells its view's rays cross: rays cast
/// from the sensor through a pinhole image of the view's field of view, each walked by the
/// project's one grid walk (map/traversal.hpp) until it leaves the grid, passes the maximum range
/// or has crossed its first occupied cell (which it includes, as the paper's ray casts do). A cell
/// crossed by several rays of one view counts once (a per-view stamp): the paper's sum runs over
/// the set of cells the view's rays traverse.

#include <cstddef>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "vantage/gain/free_space.hpp"
#include "vantage/gain/models/metrics/shared.hpp"
#include "vantage/gain/octant_shadows.hpp"
#include "vantage/gain/snapshot.hpp"
#include "vantage/gain/types.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// The fast evaluation casts every kFastSubsample-th ray of the exact one along each image axis,
/// as rpg subsamples the camera image.
inline constexpr int kFastSubsample = 3;

/// The metric `config.method` names for every view. kExact casts rays at most
/// `config.ray_spacing` cells apart at the farthest cell in view (1/sqrt(2) by default: every cell
/// in view is crossed by a ray), kFast and kAuto every kFastSubsample-th of those rays along each
/// axis. `ViewGain::gain` is the metric's value; `ViewGain::cells` and `targets` the unobserved
/// cells the rays reach before their first occupied cell, counted once (the unobserved-voxel
/// count). The rays cross free space by the jumping walk of models/metric_rays.hpp (docs/model.md,
/// "The metrics at speed"). Deterministic for any thread count. Throws std::invalid_argument for
/// another method.
std::vector<ViewGain> metric_view_gains(const GainMap& map, std::span<const Frustum> views,
                                        const GainConfig& config);

/// The same on the grid, which is only read.
std::vector<ViewGain> metric_view_gains(const OccupancyGrid& grid, std::span<const Frustum> views,
                                        const GainConfig& config);

namespace detail {

struct Spaces;

/// What a metric whose rays must pass near an occupied cell to change it needs of the occupied
/// cells (detail::reach_cells, models/metric_type.hpp), found in one pass over the grid.
struct OccupiedCells {
  /// The box of their centres [m], empty when none is (MetricContext::occupied): for the rear
  /// side metrics and those that read distances; unset for the others.
  std::optional<Eigen::AlignedBox3d> box;
  /// For the rear side metrics, the cubes of blocks that hold none (MetricContext::open); else
  /// empty.
  FreeSpace open;
};

}  // namespace detail

/// metric_view_gains on one map for several sets of views and ray pitches: the snapshot, its free
/// cubes and the distances are built once (a decision that evaluates views in rounds, the swept
/// search's metric race, docs/decision.md).
class MetricEvaluator {
 public:
  /// Throws std::invalid_argument when `config` is invalid or names no metric.
  MetricEvaluator(const OccupancyGrid& grid, const GainConfig& config);
  /// Every view's value as metric_view_gains gives it when `coarseness` is 1; else an estimate of
  /// it by every coarseness-th of its rays along each image axis, each cell weighed by about how
  /// many cells the metric's own rays cross for each the coarser rays cross at its distance
  /// (detail::RayCell::weight).
  /// With `count_cells` false, ViewGain::cells is 0 and the proximity count crosses cubes of
  /// free cells and unobserved ones beyond D of every occupied cell in one step too, the rear
  /// side metrics walk in full only the rays that end on a rear side (found by a probe across
  /// cubes of blocks with no occupied cell), and a metric listed cell by cell walks only the
  /// rays that may credit a cell (models/credit_rays.hpp): the same values to the last bit.
  std::vector<ViewGain> gains(std::span<const Frustum> views, int coarseness = 1,
                              bool count_cells = true) const;

  /// Whether the metric's value is a sum of what each cell is credited (the surface model and
  /// the proximity count; models/metric_cells.hpp): cells() then lists it cell by cell.
  bool lists_cells() const;
  /// The cells such a metric may credit, ascending: the unobserved cells within D of an occupied
  /// cell; empty for another metric.
  const std::vector<std::uint32_t>& creditable() const { return creditable_; }
  /// Per cell, its distance to the nearest occupied cell [cells] (occupied_distance, within D),
  /// for a metric that reads distances; empty for another.
  const std::vector<float>& distances() const { return near_; }
  /// For such a metric, the occupied cells' shadows (OctantShadows), which its lists read; empty
  /// for another.
  const OctantShadows& shadows() const { return shadows_; }
  /// Per cell of the map, how many bits earlier a race's samples take it (cells_by_sample's
  /// boost): a creditable cell 3 less its distance class (surface_class), so that a cell face to
  /// face with a surface is sampled 8 times as often as one 4 cells off, as both metrics credit it
  /// more (the surface model by its fitted rates, the proximity count by D - d); 0 for the
  /// others.
  std::vector<std::uint8_t> sample_boost() const;
  /// Every view's credits on `cells` (linear indices, ascending) at the metric's own pitch: the
  /// cells credited more than 0 with their credits, summing over creditable() to gains()' value
  /// up to the order of the additions. The same for any thread count. `stopped`, empty or one per
  /// view, keeps the rays each view's walks saw stopped across calls of this evaluator for the
  /// same views, so that a race's later rounds walk fewer (StoppedRays; the same credits whatever
  /// such calls left in it). Throws
  /// std::invalid_argument when the metric's value is not such a sum.
  std::vector<ViewCells> cells(std::span<const Frustum> views, std::span<const std::uint32_t> cells,
                               std::span<StoppedRays* const> stopped = {}) const;

 private:
  /// The cubes and box the jumping walk crosses.
  detail::Spaces spaces() const;

  GainConfig config_;
  GainMap map_;  // of the classes alone for a metric that lists cells (GainMap::of_classes)
  FreeSpace free_, uniform_;  // uniform_ empty when the metric crosses none
  // Per block of the census: it holds or touches an occupied cell's block (within D of one).
  std::vector<std::uint8_t> near_blocks_;
  std::vector<float> near_;
  FreeSpace far_;  // empty when the metric crosses none
  detail::OccupiedCells occupied_;
  std::vector<std::uint32_t> creditable_;
  // Empty unless the metric's value is a sum of cell credits: what its lists read.
  OctantShadows shadows_;
  std::vector<std::uint8_t> reach_;  // detail::reach_codes
  FreeSpace far_unobserved_;         // detail::MetricContext::far_unobserved
};

/// The reference the evaluation above is held to (tests/gain/metrics_test.cpp): the same rays,
/// each walked cell by cell and every cell handed to the metric, where metric_view_gains crosses
/// free cubes in one step where the metric allows (docs/model.md, "The metrics at speed").
std::vector<ViewGain> metric_view_gains_reference(const GainMap& map,
                                                  std::span<const Frustum> views,
                                                  const GainConfig& config);

}  // namespace vantage
