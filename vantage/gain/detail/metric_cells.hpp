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

#include "vantage/gain/detail/metric_rays.hpp"

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
    u_lo = std::min(u_lo, q.y() / q.x());
    u_hi = std::max(u_hi, q.y() / q.x());
    v_lo = std::min(v_lo, q.z() / q.x());
    v_hi = std::max(v_hi, q.z() / q.x());
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

/// One view's credits under `Metric` (cell_sum) on `cells`, linear indices ascending: each cell's
/// credit by the first of the view's rays (view_rays' order: rows, then columns) that reaches it,
/// the cells credited more than 0 listed (ViewCells::seen: the credits; ViewCells::targets: the
/// cells some ray of the view's image may pass through). The sum of the credits of all cells is
/// view_rays' value at the metric's own pitch without cell counts, up to the order of the
/// additions. `taken` has a bit per cell of the map, every one set; it is left so.
template <typename Metric>
ViewCells view_cell_credits(const MetricContext& ctx, const Frustum& view,
                            std::span<const std::uint32_t> cells,
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
  with_codes(ctx.map, [&](const auto* codes) {
    for (const std::uint32_t i : cells) {
      const Index3 c = spec.unravel(i);
      int row_lo, row_hi, col_lo, col_hi;
      if (!rays_through_cell(image, spec, c, row_lo, row_hi, col_lo, col_hi)) continue;
      const Eigen::Vector3d half = Eigen::Vector3d::Constant((0.5 + kCellSpare) * spec.resolution);
      const Eigen::Vector3d lo = spec.center(c) - half, hi = spec.center(c) + half;
      Metric metric = make_metric<Metric>(ctx);
      taken[i >> 6] &= ~(std::uint64_t{1} << (i & 63));
      bool reached = false;
      for (int row = row_lo; row <= row_hi && !reached; row += image.step) {
        for (int col = col_lo; col <= col_hi && !reached; col += image.step) {
          const Eigen::Vector3d dir = image.direction(row, col);
          const Eigen::Vector3d to = o + image.max_range * dir;
          // NOTE: the walk visits the cells the segment passes through (kCellSpare).
          const auto [s_in, s_out] = clip_to_box(lo, hi, o, to - o);
          if (std::max(s_in, 0.0) > std::min(s_out, 1.0)) continue;
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
  run_with_threads(num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, views.size(), [&](std::size_t v) {
      out[v] = view_cell_credits<Metric>(ctx, views[v], cells, taken.local());
    });
  });
  return out;
}

}  // namespace vantage::detail
