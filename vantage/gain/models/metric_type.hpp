#pragma once
/// @file
/// What a metric type is (the field's metrics, one file each under metrics/; docs/model.md "The
/// field's metrics"): the cells it is handed and the traits it may declare. A metric type has
///   void begin_ray();
///   void cell(const RayCell&, Stamp& credit);   // every cell the ray crosses, in order
///   void end_ray(bool rear_side, Stamp& credit);
///   double value(double rays) const;            // once all of a view's rays are cast
/// and lives in its own file under gain/models/metrics/; gain/methods.cpp registers it. It may say
/// that the jumping walk (metric_rays.hpp) may cross free space (optional: by default it crosses
/// nothing):
///   static constexpr bool kFreeInert;  // after one free cell, more free cells change nothing
///                                      // (visibility aside, which it ignores)
/// or that free cells change only the visibility of the cells after them (the jumping walk then
/// crosses cubes of free cells of one value, multiplying the visibility by each cell's 1 - p):
///   static constexpr bool kFreeDims;
/// A free-inert metric may also say which other cells change nothing after the first of them
/// (the jumping walk crosses cubes of those too when it need not count the unobserved cells):
///   static constexpr QuietCells kQuiet;
/// A metric raced cell by cell (metric_cells.hpp) may say that every unobserved cell beyond D of
/// every occupied cell changes it alike, whatever its index and range (optional; false by
/// default): its walk by codes then crosses cubes of such cells when it need not count the
/// unobserved cells, handing the metric one such cell for each it crosses:
///   static constexpr bool kFarAlike;
/// A metric may say that only the unobserved cells within D (kProximityCells) of an occupied cell
/// change it (optional; false by default):
///   static constexpr bool kNearRays;
/// or that a ray changes it only when it ends on a rear side (optional; false by default); when
/// the walk need not count the unobserved cells, it then probes each ray first across cubes of
/// blocks with no occupied cell (MetricContext::open) and walks in full only those that do:
///   static constexpr bool kRearSideRays;
/// Either way, when the walk need not count the unobserved cells, a ray that passes no occupied
/// cell within that reach (reach_cells) is not walked (MetricContext::occupied).
/// A metric whose value is the surface a scan is expected to add [cells], by chances per cell that
/// a run fits from its own scans (MetricContext::surface_rates, SurfaceRateFit), says so
/// (optional; false by default): the run then fits them, and reports its value in cells:
///   static constexpr bool kSurfaceCells;

#include <Eigen/Geometry>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "vantage/gain/free_space.hpp"
#include "vantage/gain/models/metrics/shared.hpp"
#include "vantage/gain/octant_shadows.hpp"
#include "vantage/gain/snapshot.hpp"
#include "vantage/gain/types.hpp"

namespace vantage {

// The definitions, equations and where rpg_ig_active_reconstruction's code differs from the
// paper: docs/model.md, "The field's metrics". Entropies are in bits (the paper's in nats: a
// constant factor, the same ranking).

/// A cell as a metric sees it on its ray.
struct RayCell {
  std::size_t linear;
  const GainMap::Value& value;
  double visibility;  ///< P_v: the product of 1 - p over the ray's cells before this one
  /// Distance to the nearest occupied cell [cells], +inf beyond D; the jumping walk reads it for
  /// unobserved cells only (+inf for the others), the one class a metric reads it for.
  float near;
  bool in_range;  ///< the cell's centre lies at least the sensor's min range away
  /// What the cell stands for in an estimate by coarser rays (MetricContext::coarseness): about
  /// 1 / the share of such cells the coarser rays cross among those the metric's own rays cross,
  /// at the cell's distance; exactly 1 at the metric's own pitch. A metric that sums over cells
  /// weighs each by it.
  double weight;
};

/// Marks cells counted in the current view: one bit per cell (a 129 x 129 x 65 grid in 135 KB,
/// which stays in cache where a word per cell would not), cleared for each view.
struct Stamp {
  std::vector<std::uint64_t>& bits;
  /// When set, what add() adds, in order: the cell and its addend (the bands of one view's rays,
  /// detail::all_views_in_bands).
  std::vector<std::pair<std::uint32_t, double>>* log = nullptr;
  /// True the first time a cell is taken in this view.
  bool take(std::size_t i) {
    std::uint64_t& word = bits[i >> 6];
    const std::uint64_t bit = std::uint64_t{1} << (i & 63);
    if (word & bit) return false;
    word |= bit;
    return true;
  }
  /// The first time cell `i` is taken in this view, adds `x` to `sum` (and logs both).
  void add(std::size_t i, double x, double& sum) {
    if (!take(i)) return;
    sum += x;
    if (log != nullptr) log->emplace_back(static_cast<std::uint32_t>(i), x);
  }
  void clear() { std::fill(bits.begin(), bits.end(), std::uint64_t{0}); }
};

inline bool unknown(const RayCell& c) { return c.value.state == CellState::kUnobserved; }

// Each metric below follows one view's rays: begin_ray(), cell() for every cell the ray crosses
// in order (the last one occupied when the ray ended on one), end_ray(rear_side), where
// rear_side says the ray ended on an occupied cell right behind an unobserved one; value() once
// all rays are cast. Cells are credited once per view (Stamp).

namespace detail {

struct CreditBlocks;  // models/credit_rays.hpp

/// What the metrics of one evaluation share.
struct MetricContext {
  const GainMap& map;
  const std::vector<float>& near;   // empty when the metric needs no distances
  double spacing;                   // ray pitch at the farthest cell in view [cells]
  int subsample;                    // cast every subsample-th ray along each image axis
  const FreeSpace* free = nullptr;  // the jumping walk's free cubes; nullptr: the reference walk
  /// The cubes of free cells of one value, for a metric that free cells only dim (free_dims);
  /// nullptr: it is walked cell by cell.
  const FreeSpace* uniform = nullptr;
  /// The cubes of free cells and unobserved ones beyond D of every occupied cell (QuietCells),
  /// crossed only when the unobserved cells need not be counted.
  const FreeSpace* far = nullptr;
  /// The cubes of blocks that hold no occupied cell, probed across by a metric of rear side rays
  /// (the file's note) when the unobserved cells need not be counted; nullptr: none.
  const FreeSpace* open = nullptr;
  /// For a metric of rear side or near rays (reach_cells), the box [m] of the occupied cells'
  /// centres, empty when none is; nullptr: none given, every ray is walked.
  const Eigen::AlignedBox3d* occupied = nullptr;
  /// Whether ViewGain::cells counts the unobserved cells reached; false: 0, and a metric whose
  /// quiet cells include unobserved ones crosses their cubes in one step.
  bool count_cells = true;
  /// 1: the metric's own rays (every subsample-th); k > 1: every k-th of those along each axis,
  /// an estimate whose cells carry RayCell::weight.
  int coarseness = 1;
  /// The surface model's chances (GainConfig::surface_rates).
  SurfaceRates surface_rates = kSurfacePrior;
  /// For a metric listed cell by cell (models/metric_cells.hpp), the occupied cells' shadows,
  /// which prove cells unreached before their rays are looked at; nullptr: none.
  const OctantShadows* shadows = nullptr;
  /// For such a metric, every cell's code (reach_codes in models/metric_cells.hpp), which its
  /// lists' walks read; nullptr for another.
  const std::uint8_t* reach = nullptr;
  /// For such a metric that says kFarAlike, the cubes of unobserved cells beyond D of every
  /// occupied cell, which its walk by codes crosses in one step; nullptr: none.
  const FreeSpace* far_unobserved = nullptr;
  /// For such a metric when the unobserved cells need not be counted, the blocks of its
  /// creditable cells (credit_rays.hpp): a few views cast in bands walk only the rays that may
  /// pass one the shadows leave open; nullptr: every ray is walked.
  const CreditBlocks* credit_blocks = nullptr;
};

/// Which cells besides free ones change nothing for a metric after the first of them on a ray.
enum class QuietCells {
  kFree,  ///< none besides free cells
  kFar,   ///< unobserved cells beyond D of every occupied cell (MetricContext::far)
};

template <typename Metric>
constexpr QuietCells quiet_cells() {
  if constexpr (requires { Metric::kQuiet; }) {
    return Metric::kQuiet;
  } else {
    return QuietCells::kFree;
  }
}

/// Whether free cells only dim `Metric`'s later cells (the file's note); false unless it says so.
template <typename Metric>
constexpr bool free_dims() {
  if constexpr (requires { Metric::kFreeDims; }) {
    return Metric::kFreeDims;
  } else {
    return false;
  }
}

/// Whether every unobserved cell beyond D changes `Metric` alike (the file's note); false unless
/// it says so.
template <typename Metric>
constexpr bool far_alike() {
  if constexpr (requires { Metric::kFarAlike; }) {
    return Metric::kFarAlike;
  } else {
    return false;
  }
}

/// Whether `Metric` is free-inert (the file's note); false unless it says so.
template <typename Metric>
constexpr bool free_inert() {
  if constexpr (requires { Metric::kFreeInert; }) {
    return Metric::kFreeInert;
  } else {
    return false;
  }
}

/// Whether only rays that end on a rear side change `Metric` (the file's note); false unless it
/// says so.
template <typename Metric>
constexpr bool rear_side_rays() {
  if constexpr (requires { Metric::kRearSideRays; }) {
    return Metric::kRearSideRays;
  } else {
    return false;
  }
}

/// Whether `Metric`'s value is the surface a scan adds, by fitted chances (the file's note).
template <typename Metric>
constexpr bool surface_cells() {
  if constexpr (requires { Metric::kSurfaceCells; }) {
    return Metric::kSurfaceCells;
  } else {
    return false;
  }
}

/// How near an occupied cell's centre a ray must pass, on every axis, to change `Metric` (the
/// file's note) [cells]: 0 for rear side rays (they end on one), D for near rays (the cells they
/// credit lie within D of one); negative when any ray may change it.
template <typename Metric>
constexpr double reach_cells() {
  if constexpr (rear_side_rays<Metric>()) {
    return 0.0;
  } else if constexpr (requires { Metric::kNearRays; }) {
    return Metric::kNearRays ? kProximityCells : -1.0;
  } else {
    return -1.0;
  }
}

}  // namespace detail
}  // namespace vantage
