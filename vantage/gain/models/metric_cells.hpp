#pragma once
/// @file
/// A metric's value cell by cell (docs/decision.md, "The surface model raced"): for a metric whose
/// value is the sum of what each cell is credited, once, by the first of the view's rays that
/// reaches it, a cell's credit is found by walking only the few rays of the view's image that pass
/// through it, in the order view_rays casts them, up to the cell. Listed on a sample of the cells,
/// the credits give the view's value on the sample, which the swept search's race compares between
/// views (planner/searches/race.hpp) as it compares the target models' visibilities. A metric says
/// that its value is such a sum (optional; false by default):
///   static constexpr bool kCellSum;  // value() is the sum of the credits cell() gives, and a
///                                    // cell's credit depends on the cells before it on its ray
/// Only the unobserved cells within D of an occupied cell (kNearRays) are credited.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "vantage/gain/models/metric_rays.hpp"

namespace vantage::detail {

/// Whether `Metric`'s value is a sum of cell credits (the file's note); false unless it says so.
template <typename Metric>
constexpr bool cell_sum() {
  if constexpr (requires { Metric::kCellSum; }) {
    return Metric::kCellSum && reach_cells<Metric>() == kProximityCells;
  } else {
    return false;
  }
}

/// How far past a cell's faces a ray is still taken to pass through it, and past its image a ray
/// to pass through that [cells, rays]: a walk's boundaries are computed to about 1e-15 of the
/// segment, so a ray any farther cannot visit the cell.
inline constexpr double kCellSpare = 1e-6;

/// The rows [row_lo, row_hi] and columns [col_lo, col_hi] of `image`'s lattice (first + j step)
/// whose rays may pass through the cell `c`; false when none may.
inline bool rays_through_cell(const RayImage& image, const GridSpec& spec, const Index3& c,
                              int& row_lo, int& row_hi, int& col_lo, int& col_hi) {
  const Eigen::Vector3d centre = image.R.transpose() * (spec.center(c) - image.origin);
  const Eigen::Matrix3d half = image.R.transpose() * (0.5 * spec.resolution);
  double u_lo = std::numeric_limits<double>::infinity(), u_hi = -u_lo, v_lo = u_lo, v_hi = -u_lo;
  bool behind = false;
  for (int corner = 0; corner < 8; ++corner) {
    Eigen::Vector3d q = centre;
    for (int a = 0; a < 3; ++a) q += ((corner >> a) & 1 ? 1.0 : -1.0) * half.col(a);
    if (!(q.x() > 0.0)) {
      behind = true;
      break;
    }
    const double inverse = 1.0 / q.x();
    u_lo = std::min(u_lo, q.y() * inverse);
    u_hi = std::max(u_hi, q.y() * inverse);
    v_lo = std::min(v_lo, q.z() * inverse);
    v_hi = std::max(v_hi, q.z() * inverse);
  }
  // Ray k of an axis lies at -tan + (k + 0.5) pitch: those from the first at or above `lo` to
  // the last at or below `hi`, widened by kCellSpare of a pitch for the rounding, on the lattice.
  const auto range = [&](double lo, double hi, double tan, double pitch, int n, int& k_lo,
                         int& k_hi) {
    int a = image.first, b = n - 1;
    if (!behind) {
      // NOTE: clamped before the cast, which a cell near the image plane would overflow.
      const double most = 1e8;
      a = std::max(a, static_cast<int>(std::clamp(std::ceil((lo + tan) / pitch - 0.5 - kCellSpare),
                                                  -most, most)));
      b = std::min(b, static_cast<int>(std::clamp(std::floor((hi + tan) / pitch - 0.5 + kCellSpare),
                                                  -most, most)));
    }
    k_lo = image.first + (a - image.first + image.step - 1) / image.step * image.step;
    k_hi = b;
    return k_lo <= k_hi;
  };
  return range(u_lo, u_hi, image.tan_h, image.su, image.cols, col_lo, col_hi) &&
         range(v_lo, v_hi, image.tan_v, image.sv, image.rows, row_lo, row_hi);
}

/// How many cells before a target `blocked_before` looks back along a ray at most.
inline constexpr int kLookBack = 64;

/// Whether an occupied cell lies on the segment o + s d (s in [0, 1]) before the cell `target`,
/// found by walking back from the target along the segment: a proof that a walk of that segment
/// (walk_ray, which ends on the first occupied cell it enters) does not reach the target. An
/// occupied cell counts only when the segment passes through its cube shrunk by kCellSpare and
/// leaves that before it enters the target's cube, so that no rounding of the walk's boundaries
/// can step around it or put it after the target; false proves nothing.
///
/// The steps back stop after `cells` cells, at the grid's edge, at the origin, and on a free cell
/// or an unobserved one beyond D of every occupied cell (`near`, occupied_distance): a listed
/// cell lies within D of an occupied one, and most rays to it that do not reach it end on that
/// surface, a few cells back; past it, in free space or a deep shadow, the walk forward is the
/// cheaper way to the answer (it crosses free space in cubes; docs/decision.md, "A metric raced
/// cell by cell").
template <typename Code>
bool blocked_before(const GridSpec& spec, std::span<const GainMap::Value> values, const Code* codes,
                    std::span<const float> near, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                    const Index3& target, int cells = kLookBack) {
  const auto clip = [&](const Index3& cell, double grow) {
    const Eigen::Vector3d lo = spec.origin + cell.cast<double>() * spec.resolution;
    return clip_to_box(lo.array() - grow * spec.resolution,
                       (lo.array() + (1.0 + grow) * spec.resolution).matrix(), o, d);
  };
  const auto [t_in, t_out] = clip(target, 0.0);
  if (!(t_in < t_out)) return false;
  // NOTE: the project's walk, from the middle of the segment's part in the target back to the
  // origin; only an occupied cell's own clip decides, so the walk's rounding cannot.
  GridWalk walk(spec, o + 0.5 * (t_in + t_out) * d, o);
  if (!walk.entered()) return false;
  for (int k = 0; k < cells && !walk.at_end(); ++k) {
    walk.advance();
    if (walk.ends_outside() && !spec.contains(walk.cell())) return false;  // left the grid
    const CellState state = values[codes[walk.linear()]].state;
    if (state == CellState::kFree) return false;
    if (state == CellState::kUnobserved) {
      if (!near.empty() && near[walk.linear()] > kProximityCells) return false;
      continue;
    }
    const auto [x_in, x_out] = clip(walk.cell(), -kCellSpare);
    if (x_in < x_out && x_out <= t_in && x_in >= 0.0) return true;
  }
  return false;
}

/// One view's credits under `Metric` (cell_sum) on `cells`, linear indices ascending: each cell's
/// credit by the first of the view's rays (view_rays' order: rows, then columns) that reaches it,
/// the cells credited more than 0 listed (ViewCells::seen: the credits; ViewCells::targets: the
/// cells some ray of the view's image may pass through). The sum of the credits of all cells is
/// view_rays' value at the metric's own pitch without cell counts, up to the order of the
/// additions. `at` holds the cells' indices (GridSpec::unravel). `taken` has a bit per cell of the
/// map, every one set; it is left so. A ray that blocked_before proves not to reach the cell is not
/// walked: the same credits, bit for bit.
template <typename Metric>
ViewCells view_cell_credits(const MetricContext& ctx, const Frustum& view,
                            std::span<const std::uint32_t> cells, std::span<const Index3> at,
                            std::vector<std::uint64_t>& taken) {
  static_assert(cell_sum<Metric>(), "the metric's value is not a sum of cell credits");
  const GridSpec& spec = ctx.map.spec();
  const RayImage image(spec, ctx.spacing, ctx.subsample, 1, view);
  const Eigen::Vector3d& o = image.origin;
  // NOTE: a stamp that takes no cell but the one listed: every bit set but its own.
  Stamp credit{taken};
  std::vector<std::uint64_t> no_marks;
  Stamp seen{no_marks};
  ViewCells out;
  const std::span<const GainMap::Value> values = ctx.map.values();
  const double half = (0.5 + kCellSpare) * spec.resolution;
  with_codes(ctx.map, [&](const auto* codes) {
    for (std::size_t k = 0; k < cells.size(); ++k) {
      const std::uint32_t i = cells[k];
      const Index3& c = at[k];
      int row_lo, row_hi, col_lo, col_hi;
      if (!rays_through_cell(image, spec, c, row_lo, row_hi, col_lo, col_hi)) continue;
      const Eigen::Vector3d lo = spec.center(c).array() - half, hi = spec.center(c).array() + half;
      Metric metric = make_metric<Metric>(ctx);
      taken[i >> 6] &= ~(std::uint64_t{1} << (i & 63));
      bool reached = false;
      for (int row = row_lo; row <= row_hi && !reached; row += image.step) {
        for (int col = col_lo; col <= col_hi && !reached; col += image.step) {
          const Eigen::Vector3d to = o + image.max_range * image.direction(row, col);
          const Eigen::Vector3d d = to - o;
          // NOTE: the walk visits the cells the segment passes through (kCellSpare).
          const auto [s_in, s_out] = clip_to_box(lo, hi, o, d);
          if (std::max(s_in, 0.0) > std::min(s_out, 1.0)) continue;
          // NOTE: most rays to a listed cell end on the surface it lies next to.
          if (blocked_before(spec, values, codes, ctx.near, o, d, c)) continue;
          GridWalk walk(spec, o, to);
          if (!walk.entered()) continue;
          ViewGain unused;
          metric.begin_ray();
          reached = walk_ray(ctx, image, codes, walk, metric, credit, seen, unused, &c).reached;
        }
      }
      taken[i >> 6] |= std::uint64_t{1} << (i & 63);
      const double value = metric.value(1.0);
      if (value > 0.0) {
        out.cells.push_back(i);
        out.seen.push_back(value);
      }
      ++out.targets;
    }
  });
  return out;
}

/// Every view's credits under `Metric` on `cells` (view_cell_credits); views in parallel, each
/// listed in cell order, so the same for any thread count.
template <typename Metric>
std::vector<ViewCells> all_view_cells(const MetricContext& ctx, std::span<const Frustum> views,
                                      std::span<const std::uint32_t> cells, int num_threads) {
  std::vector<ViewCells> out(views.size());
  const std::size_t words = (ctx.map.size() + 63) / 64;
  tbb::enumerable_thread_specific<std::vector<std::uint64_t>> taken(
      [words] { return std::vector<std::uint64_t>(words, ~std::uint64_t{0}); });
  std::vector<Index3> at(cells.size());
  for (std::size_t k = 0; k < cells.size(); ++k) at[k] = ctx.map.spec().unravel(cells[k]);
  run_with_threads(num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, views.size(), [&](std::size_t v) {
      out[v] = view_cell_credits<Metric>(ctx, views[v], cells, at, taken.local());
    });
  });
  return out;
}

}  // namespace vantage::detail
