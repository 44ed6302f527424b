#pragma once
/// @file
/// The ray casting the field's metrics share (metrics.hpp): a pinhole image of rays per view, each
/// walked until its first occupied cell, feeding a metric type. A metric type has
///   void begin_ray();
///   void cell(const RayCell&, Stamp& credit);   // every cell the ray crosses, in order
///   void end_ray(bool rear_side, Stamp& credit);
///   double value(double rays) const;            // once all of a view's rays are cast
/// and lives in its own file under gain/metrics/; gain/methods.cpp registers it. It may say that
/// the jumping walk below may cross free space (optional: by default it crosses nothing):
///   static constexpr bool kFreeInert;  // after one free cell, more free cells change nothing
///                                      // (visibility aside, which it ignores)
/// or that free cells change only the visibility of the cells after them (the jumping walk then
/// crosses cubes of free cells of one value, multiplying the visibility by each cell's 1 - p):
///   static constexpr bool kFreeDims;
/// A free-inert metric may also say which other cells change nothing after the first of them
/// (the jumping walk crosses cubes of those too when it need not count the unobserved cells):
///   static constexpr QuietCells kQuiet;
/// A metric may say that only the unobserved cells within D (kProximityCells) of an occupied cell
/// change it (optional; false by default):
///   static constexpr bool kNearRays;
/// or that a ray changes it only when it ends on a rear side (optional; false by default); when
/// the walk need not count the unobserved cells, it then probes each ray first across cubes of
/// blocks with no occupied cell (MetricContext::open) and walks in full only those that do:
///   static constexpr bool kRearSideRays;
/// Either way, when the walk need not count the unobserved cells, a ray that passes no occupied
/// cell within that reach (reach_cells) is not walked (MetricContext::occupied).
///
/// One walk feeds it (`view_rays`), in two ways: the reference hands the metric every cell of
/// every ray; the jumping walk (docs/model.md "The metrics at speed") casts only the rays that
/// meet the grid and, for a free-inert metric, crosses whole cubes of free cells (FreeSpace) in
/// one step.

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

#include "vantage/gain/detail/ray_image.hpp"
#include "vantage/gain/free_space.hpp"
#include "vantage/gain/metrics/shared.hpp"
#include "vantage/gain/octant_shadows.hpp"
#include "vantage/gain/snapshot.hpp"
#include "vantage/gain/types.hpp"
#include "vantage/map/traversal.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/views/frustum.hpp"

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
  /// True the first time a cell is taken in this view.
  bool take(std::size_t i) {
    std::uint64_t& word = bits[i >> 6];
    const std::uint64_t bit = std::uint64_t{1} << (i & 63);
    if (word & bit) return false;
    word |= bit;
    return true;
  }
  void clear() { std::fill(bits.begin(), bits.end(), std::uint64_t{0}); }
};

inline bool unknown(const RayCell& c) { return c.value.state == CellState::kUnobserved; }

// Each metric below follows one view's rays: begin_ray(), cell() for every cell the ray crosses
// in order (the last one occupied when the ray ended on one), end_ray(rear_side), where
// rear_side says the ray ended on an occupied cell right behind an unobserved one; value() once
// all rays are cast. Cells are credited once per view (Stamp).

namespace detail {

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
  /// For a metric listed cell by cell (detail/metric_cells.hpp), the occupied cells' shadows,
  /// which prove cells unreached before their rays are looked at; nullptr: none.
  const OctantShadows* shadows = nullptr;
  /// For such a metric, every cell's code (reach_codes in detail/metric_cells.hpp), which its
  /// lists' walks read; nullptr for another.
  const std::uint8_t* reach = nullptr;
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

/// Whether the walk ends on a rear side, an occupied cell right after an unobserved one, as the
/// reference walk finds it: the same cells, but the cubes of `open` (no occupied cell) crossed in
/// one step. Landing on an occupied cell, the cell before it is the cube's cell face to face with
/// it: the landing cell pulled back into the cube.
template <typename Code>
bool ends_on_rear_side(GridWalk walk, const GridSpec& spec, const Code* codes,
                       std::span<const GainMap::Value> values, const FreeSpace& open) {
  bool previous_unknown = false;
  for (;;) {
    const CellState state = values[codes[walk.linear()]].state;
    if (state == CellState::kOccupied) return previous_unknown;
    previous_unknown = state == CellState::kUnobserved;
    if (const int e = open.extent_at(walk.octant(), walk.cell()); e > 0) {
      Index3 lo, hi;
      FreeSpace::cube(walk.cell(), walk.octant(), e, spec.dims, lo, hi);
      if ((walk.end().array() < lo.array()).any() || (walk.end().array() > hi.array()).any()) {
        walk.leave_box(lo, hi);
        if (!spec.contains(walk.cell())) return false;  // left the grid
        const Index3 before = walk.cell().cwiseMax(lo).cwiseMin(hi);
        previous_unknown = values[codes[spec.linear(before)]].state == CellState::kUnobserved;
        continue;
      }
    }
    if (walk.at_end()) return false;
    walk.advance();
    if (walk.ends_outside() && !spec.contains(walk.cell())) return false;  // left the grid
  }
}

/// How one ray's walk ended (walk_ray).
struct RayEnd {
  bool rear_side = false;  ///< it ended on an occupied cell right after an unobserved one
  bool reached = false;    ///< it reached the target cell it was walked to
};

/// Walks one ray of `image` from the walk's first cell, handing every cell to `metric` in order
/// (the file's note), crossing the cubes the metric allows; counts the unobserved cells reached
/// into `result` when the context asks. With a `target` cell, stops in it (RayEnd::reached) or
/// once the walk has passed it on an axis, where a walk, moving in one octant, never comes back.
template <typename Metric, typename Code>
RayEnd walk_ray(const MetricContext& ctx, const RayImage& image, const Code* codes, GridWalk& walk,
                Metric& metric, Stamp& credit, Stamp& seen, ViewGain& result,
                const Index3* target = nullptr) {
  const GridSpec& spec = ctx.map.spec();
  const FreeSpace* free = ctx.free;
  const std::span<const GainMap::Value> values = ctx.map.values();
  const float far = std::numeric_limits<float>::infinity();
  const int octant = walk.octant();
  double visibility = 1.0;
  bool previous_unknown = false;
  for (;;) {
    if (target != nullptr) {
      for (int a = 0; a < 3; ++a) {
        const int ahead =
            ((octant >> a) & 1) ? walk.cell()[a] - (*target)[a] : (*target)[a] - walk.cell()[a];
        if (ahead > 0) return {};  // passed it
      }
    }
    const std::size_t linear = walk.linear();
    const GainMap::Value& v = values[codes[linear]];
    double r2 = 0.0;
    if (!image.all_in_range || image.weight_scale > 0.0) {
      r2 = (spec.center(walk.cell()) - image.origin).squaredNorm();
    }
    const bool in_range = image.all_in_range || r2 >= image.min_r2;
    const double weight = image.weight_scale > 0.0
                              ? std::clamp(image.weight_scale * r2, 1.0, image.most_weight)
                              : 1.0;
    // NOTE: the distance read for unobserved cells only (RayCell::near): otherwise 4 bytes
    // a cell from a table four times the codes' size; 10-20 % of the CPU time of
    // proximity count and area factor on BM_MetricDecision187.
    const bool unobserved = v.state == CellState::kUnobserved;
    metric.cell(RayCell{linear, v, visibility,
                        unobserved && !ctx.near.empty() ? ctx.near[linear] : far, in_range, weight},
                credit);
    if (target != nullptr && walk.cell() == *target) return {false, true};
    if (v.state == CellState::kOccupied) return {previous_unknown, false};
    previous_unknown = unobserved;
    if (ctx.count_cells && previous_unknown && in_range && seen.take(linear)) {
      result.cells += weight;
    }
    visibility *= 1.0 - v.p;  // eq. M1
    if constexpr (quiet_cells<Metric>() == QuietCells::kFar) {
      const bool quiet =
          v.state == CellState::kFree || (unobserved && ctx.near[linear] > kProximityCells);
      if (!ctx.count_cells && ctx.far != nullptr && quiet && ctx.far->cross(walk, spec)) {
        if (!spec.contains(walk.cell())) return {};  // left the grid
        continue;
      }
    }
    if (free_inert<Metric>() && free != nullptr && v.state == CellState::kFree &&
        free->cross(walk, spec)) {
      if (!spec.contains(walk.cell())) return {};  // left the grid
      continue;
    }
    if (free_dims<Metric>() && ctx.uniform != nullptr && v.state == CellState::kFree) {
      const Index3 from = walk.cell();
      if (ctx.uniform->cross(walk, spec)) {
        // NOTE: the cells crossed between are free and of this cell's value: the visibility
        // the reference's steps leave, one factor at a time, so to the last bit.
        const int between = (walk.cell() - from).cwiseAbs().sum() - 1;
        for (int k = 0; k < between; ++k) visibility *= 1.0 - v.p;
        if (!spec.contains(walk.cell())) return {};  // left the grid
        continue;
      }
    }
    if (walk.at_end()) return {};
    walk.advance();
    if (walk.ends_outside() && !spec.contains(walk.cell())) return {};  // left the grid
  }
}

/// The box a ray of `Metric` must meet to change it when the context need not count the
/// unobserved cells (reach_cells): the occupied cells' centres, the reach and 1.5 cells to spare
/// (half a cell to a cell's faces, a cell for the rounding of the walk's indices); none when every
/// ray may change it.
template <typename Metric>
std::optional<Eigen::AlignedBox3d> reach_box(const MetricContext& ctx) {
  if constexpr (reach_cells<Metric>() >= 0.0) {
    if (!ctx.count_cells && ctx.occupied != nullptr) {
      Eigen::AlignedBox3d reach = *ctx.occupied;
      if (!reach.isEmpty()) {
        const Eigen::Vector3d spare =
            Eigen::Vector3d::Constant((reach_cells<Metric>() + 1.5) * ctx.map.spec().resolution);
        reach = Eigen::AlignedBox3d(reach.min() - spare, reach.max() + spare);
      }
      return reach;
    }
  }
  return std::nullopt;
}

/// The walk view_rays hands each ray to by default: walk_ray, on the snapshot.
struct SnapshotWalk {
  template <typename Metric, typename Code>
  RayEnd operator()(const MetricContext& ctx, const RayImage& image, const Code* codes,
                    GridWalk& walk, Metric& metric, Stamp& credit, Stamp& seen,
                    ViewGain& result) const {
    return walk_ray(ctx, image, codes, walk, metric, credit, seen, result);
  }
};

/// Casts one view's rays and feeds them to `metric`; returns the metric's value and the count of
/// unobserved cells reached. With the context's free cubes, the jumping walk: only the rays that
/// meet the grid, and a free-inert metric's rays cross free cubes in one step (GridWalk::leave_box,
/// which lands where stepping lands), the reference's values to the last bit (docs/model.md, "The
/// metrics at speed"). Without, the reference: every ray, cell by cell. Each ray is walked by
/// `walk_one` (SnapshotWalk's signature), which must hand the metric what walk_ray hands it.
template <typename Metric, typename Walk = SnapshotWalk>
ViewGain view_rays(const MetricContext& ctx, const Frustum& view, Metric& metric, Stamp& credit,
                   Stamp& seen, const Walk& walk_one = {}) {
  const GridSpec& spec = ctx.map.spec();
  const RayImage image(ctx.map.spec(), ctx.spacing, ctx.subsample, ctx.coarseness, view);
  const Eigen::Vector3d& o = image.origin;
  int row_lo = image.first, row_hi = image.rows, col_lo = image.first, col_hi = image.cols;
  if (ctx.free != nullptr) image.rays_on_grid(spec, row_lo, row_hi, col_lo, col_hi);
  const std::optional<Eigen::AlignedBox3d> reach = reach_box<Metric>(ctx);
  return with_codes(ctx.map, [&](const auto* codes) {
    ViewGain result;
    for (int row = row_lo; row < row_hi; row += image.step) {
      for (int col = col_lo; col < col_hi; col += image.step) {
        const Eigen::Vector3d dir = image.direction(row, col);
        metric.begin_ray();
        const Eigen::Vector3d to = o + image.max_range * dir;
        if (reach.has_value()) {
          const auto [s_in, s_out] = clip_to_box(reach->min(), reach->max(), o, to - o);
          if (reach->isEmpty() || std::max(s_in, 0.0) > std::min(s_out, 1.0)) {
            metric.end_ray(false, credit);  // the segment passes no occupied cell near enough
            continue;
          }
        }
        GridWalk walk(spec, o, to);
        if (!walk.entered()) {
          metric.end_ray(false, credit);
          continue;
        }
        if constexpr (rear_side_rays<Metric>()) {
          if (!ctx.count_cells && ctx.open != nullptr &&
              !ends_on_rear_side(walk, spec, codes, ctx.map.values(), *ctx.open)) {
            metric.end_ray(false, credit);
            continue;
          }
        }
        metric.end_ray(walk_one(ctx, image, codes, walk, metric, credit, seen, result).rear_side,
                       credit);
      }
    }
    result.gain = metric.value(image.count());
    result.targets = static_cast<std::size_t>(result.cells);
    return result;
  });
}

/// A metric for one view: from the context when it reads settings from it (the surface model's
/// rates), else default-constructed.
template <typename Metric>
Metric make_metric(const MetricContext& ctx) {
  if constexpr (std::is_constructible_v<Metric, const MetricContext&>) {
    return Metric(ctx);
  } else {
    return Metric{};
  }
}

/// Every view's value under `Metric`; views in parallel, each view's rays in order on one thread,
/// so the result does not depend on threads. The jumping walk when the context has free cubes;
/// each ray walked by `Walk` (view_rays).
template <typename Metric, typename Walk = SnapshotWalk>
std::vector<ViewGain> all_views(const MetricContext& ctx, std::span<const Frustum> views,
                                int num_threads) {
  std::vector<ViewGain> gains(views.size());
  struct Marks {
    std::vector<std::uint64_t> credit, seen;
  };
  const std::size_t words = (ctx.map.size() + 63) / 64;
  tbb::enumerable_thread_specific<Marks> marks([words] {
    return Marks{std::vector<std::uint64_t>(words, 0), std::vector<std::uint64_t>(words, 0)};
  });
  run_with_threads(num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, views.size(), [&](std::size_t v) {
      Marks& m = marks.local();
      Stamp credit{m.credit}, seen{m.seen};
      credit.clear();
      seen.clear();
      Metric metric = make_metric<Metric>(ctx);
      gains[v] = view_rays(ctx, views[v], metric, credit, seen, Walk{});
    });
  });
  return gains;
}

}  // namespace detail
}  // namespace vantage
