#pragma once
/// @file
/// The ray casting the field's metrics share (evaluators/metric_evaluator.hpp): a pinhole image of
/// rays per view, each walked until its first occupied cell, feeding a metric type
/// (metric_type.hpp: what it is handed, the traits it may declare).
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
#include <limits>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

#include "vantage/gain/free_space.hpp"
#include "vantage/gain/models/metric_type.hpp"
#include "vantage/gain/models/ray_image.hpp"
#include "vantage/gain/snapshot.hpp"
#include "vantage/gain/types.hpp"
#include "vantage/map/traversal.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage::detail {

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

/// Whether a walk moving in `octant` has passed `target` on an axis: it never comes back.
inline bool walked_past(const GridWalk& walk, int octant, const Index3& target) {
  for (int a = 0; a < 3; ++a) {
    const int ahead = ((octant >> a) & 1) ? walk.cell()[a] - target[a] : target[a] - walk.cell()[a];
    if (ahead > 0) return true;
  }
  return false;
}

/// Walks one ray of `image` from the walk's first cell, handing every cell to `metric` in order
/// (metric_type.hpp), crossing the cubes the metric allows; counts the unobserved cells reached
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
    if (target != nullptr && walked_past(walk, octant, *target)) return {};
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
    if (ctx.count_cells && previous_unknown && in_range) seen.add(linear, weight, result.cells);
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
/// `walk_one` (SnapshotWalk's signature), which must hand the metric what walk_ray hands it. Of
/// the image's rows, only band `band` of `bands` bands of consecutive rows, as even as they come.
/// `walked`, empty or one byte a ray of the image's lattice (row * cols + col): the rays marked 0
/// are not walked (rays_that_may_credit: rays that credit nothing).
template <typename Metric, typename Walk = SnapshotWalk>
ViewGain view_rays(const MetricContext& ctx, const Frustum& view, Metric& metric, Stamp& credit,
                   Stamp& seen, const Walk& walk_one = {}, int band = 0, int bands = 1,
                   std::span<const std::uint8_t> walked = {}) {
  const GridSpec& spec = ctx.map.spec();
  const RayImage image(ctx.map.spec(), ctx.spacing, ctx.subsample, ctx.coarseness, view);
  const Eigen::Vector3d& o = image.origin;
  int row_lo = image.first, row_hi = image.rows, col_lo = image.first, col_hi = image.cols;
  if (ctx.free != nullptr) image.rays_on_grid(spec, row_lo, row_hi, col_lo, col_hi);
  if (bands > 1) {
    const long long rows = std::max(0, row_hi - row_lo + image.step - 1) / image.step;
    const auto row_at = [&](int b) {
      return row_lo + image.step * static_cast<int>(rows * b / bands);
    };
    const int first = row_at(band), last = row_at(band + 1);
    row_lo = first;
    row_hi = std::min(row_hi, last);
  }
  const std::optional<Eigen::AlignedBox3d> reach = reach_box<Metric>(ctx);
  return with_codes(ctx.map, [&](const auto* codes) {
    ViewGain result;
    for (int row = row_lo; row < row_hi; row += image.step) {
      for (int col = col_lo; col < col_hi; col += image.step) {
        metric.begin_ray();
        if (!walked.empty() && walked[static_cast<std::size_t>(row) * image.cols + col] == 0) {
          metric.end_ray(false, credit);
          continue;
        }
        const Eigen::Vector3d dir = image.direction(row, col);
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

}  // namespace vantage::detail
