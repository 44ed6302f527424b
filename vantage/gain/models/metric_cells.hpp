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
///                                    // through their states and distances only
///   double sum;  // the credits so far, each added by Stamp::add (all_views_in_bands joins them)
/// Only the unobserved cells within D of an occupied cell (kNearRays) are credited.

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "vantage/gain/models/metric_rays.hpp"
#include "vantage/gain/models/reach_codes.hpp"
#include "vantage/gain/octant_shadows.hpp"

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
  return image.rays_through_box(spec.center(c), Eigen::Vector3d::Constant(0.5 * spec.resolution),
                                kCellSpare, row_lo, row_hi, col_lo, col_hi);
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
/// or an unobserved one beyond D of every occupied cell (`reach`, reach_codes): a listed cell lies
/// within D of an occupied one, and most rays to it that do not reach it end on that surface, a
/// few cells back; past it, in free space or a deep shadow, the walk forward is the cheaper way to
/// the answer (it crosses free space in cubes; docs/decision.md, "A metric raced cell by cell").
inline bool blocked_before(const GridSpec& spec, const std::uint8_t* reach,
                           const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Index3& target,
                           int cells = kLookBack) {
  // NOTE: a walk of its own, in reciprocals: only an occupied cell's own clip decides, and the
  // clips' margins (kCellSpare of a cell) dwarf the reciprocals' rounding.
  const Eigen::Vector3d inv = d.cwiseInverse();
  const auto clip = [&](const Index3& cell, double grow) {
    const Eigen::Vector3d lo = spec.origin + cell.cast<double>() * spec.resolution;
    double t_in = -std::numeric_limits<double>::infinity(), t_out = -t_in;
    for (int a = 0; a < 3; ++a) {
      const double lo_a = lo[a] - grow * spec.resolution;
      const double hi_a = lo[a] + (1.0 + grow) * spec.resolution;
      if (d[a] == 0.0) {
        if (o[a] < lo_a || o[a] > hi_a) return std::pair{1.0, 0.0};
        continue;
      }
      double t0 = (lo_a - o[a]) * inv[a], t1 = (hi_a - o[a]) * inv[a];
      if (t0 > t1) std::swap(t0, t1);
      t_in = std::max(t_in, t0);
      t_out = std::min(t_out, t1);
    }
    return std::pair{t_in, t_out};
  };
  const auto [t_in, t_out] = clip(target, 0.0);
  if (!(t_in < t_out)) return false;
  // The steps back from the target towards the origin: on each axis the parameter of the next
  // face crossed, largest first.
  Index3 c = target;
  double next[3];
  double dt[3];
  int step[3];
  for (int a = 0; a < 3; ++a) {
    step[a] = d[a] > 0.0 ? -1 : 1;
    dt[a] = spec.resolution * std::abs(inv[a]);
    const double face = spec.origin[a] + (c[a] + (d[a] > 0.0 ? 0 : 1)) * spec.resolution;
    next[a] = d[a] == 0.0 ? -std::numeric_limits<double>::infinity() : (face - o[a]) * inv[a];
  }
  for (int k = 0; k < cells; ++k) {
    const int a = next[0] >= next[1] ? (next[0] >= next[2] ? 0 : 2) : (next[1] >= next[2] ? 1 : 2);
    if (!(next[a] > 0.0)) return false;  // in the origin's cell
    c[a] += step[a];
    next[a] -= dt[a];
    if (!spec.contains(c)) return false;  // left the grid
    const std::uint8_t code = reach[spec.linear(c)];
    if (code >= kFarCode && code != kOccupiedCode) return false;  // free, or beyond D
    if (code < kFarCode) continue;
    const auto [x_in, x_out] = clip(c, -kCellSpare);
    if (x_in < x_out && x_out <= t_in && x_in >= 0.0) return true;
  }
  return false;
}

/// Walks one ray of `image` as walk_ray does (the same cells handed to `metric`, the same cubes
/// crossed, the same counts), at the metric's own pitch, but reading the cells' codes (`reach`,
/// reach_codes) where walk_ray reads the snapshot and the distances: a cell-sum metric reads a
/// cell's state, distance and range only, so it is handed each cell with its state's value and its
/// distance (RayCell::visibility 1) and credits alike, bit for bit. A free cell in a block not all
/// free is stepped without a look at the free cubes, which hold no such block.
template <typename Metric>
RayEnd walk_codes(const MetricContext& ctx, const RayImage& image, const std::uint8_t* reach,
                  GridWalk& walk, Metric& metric, Stamp& credit, Stamp& seen, ViewGain& result,
                  const Index3* target = nullptr) {
  static_assert(cell_sum<Metric>() && !free_dims<Metric>());
  static const std::array<GainMap::Value, 3> kValues = {
      GainMap::Value{0.5, 1.0, CellState::kUnobserved}, GainMap::Value{0.0, 0.0, CellState::kFree},
      GainMap::Value{1.0, 0.0, CellState::kOccupied}};
  const GridSpec& spec = ctx.map.spec();
  const float far = std::numeric_limits<float>::infinity();
  const int octant = walk.octant();
  bool previous_unknown = false;
  for (;;) {
    if (target != nullptr && walked_past(walk, octant, *target)) return {};
    const std::size_t linear = walk.linear();
    const std::uint8_t code = reach[linear];
    const CellState state = code_state(code);
    const bool in_range = image.all_in_range ||
                          (spec.center(walk.cell()) - image.origin).squaredNorm() >= image.min_r2;
    metric.cell(RayCell{linear, kValues[static_cast<std::size_t>(state)], 1.0,
                        code < kFarCode ? kCodeDistance[code] : far, in_range, 1.0},
                credit);
    if (target != nullptr && walk.cell() == *target) return {false, true};
    if (state == CellState::kOccupied) return {previous_unknown, false};
    previous_unknown = state == CellState::kUnobserved;
    if (ctx.count_cells && previous_unknown && in_range) seen.add(linear, 1.0, result.cells);
    if constexpr (quiet_cells<Metric>() == QuietCells::kFar) {
      if (!ctx.count_cells && ctx.far != nullptr && code >= kFarCode &&
          ctx.far->cross(walk, spec)) {
        if (!spec.contains(walk.cell())) return {};  // left the grid
        continue;
      }
    }
    if constexpr (far_alike<Metric>()) {
      if (!ctx.count_cells && code == kFarCode && ctx.far_unobserved != nullptr) {
        const Index3 from = walk.cell();
        if (ctx.far_unobserved->cross(walk, spec)) {
          // NOTE: the cells crossed between are unobserved and beyond D, each handed to the
          // metric as a step would hand it (kFarAlike: their index and range read by none), so
          // its value is the steps' to the last bit.
          const RayCell alike{linear, kValues[0], 1.0, far, in_range, 1.0};
          const int between = (walk.cell() - from).cwiseAbs().sum() - 1;
          for (int k = 0; k < between; ++k) metric.cell(alike, credit);
          if (!spec.contains(walk.cell())) return {};  // left the grid
          continue;
        }
      }
    }
    if (free_inert<Metric>() && ctx.free != nullptr && code == kFreeBlockCode &&
        ctx.free->cross(walk, spec)) {
      if (!spec.contains(walk.cell())) return {};  // left the grid
      continue;
    }
    if (walk.at_end()) return {};
    walk.advance();
    if (walk.ends_outside() && !spec.contains(walk.cell())) return {};  // left the grid
  }
}

/// The walk a cell-sum metric's view_rays takes with the context's codes (walk_codes); walk_ray
/// without them, by the reference walk, or at a coarser pitch.
struct CodeWalk {
  template <typename Metric, typename Code>
  RayEnd operator()(const MetricContext& ctx, const RayImage& image, const Code* codes,
                    GridWalk& walk, Metric& metric, Stamp& credit, Stamp& seen,
                    ViewGain& result) const {
    if (ctx.reach == nullptr || ctx.free == nullptr || image.weight_scale > 0.0) {
      return walk_ray(ctx, image, codes, walk, metric, credit, seen, result);
    }
    return walk_codes(ctx, image, ctx.reach, walk, metric, credit, seen, result);
  }
};

/// Whether `stopped` (or null) holds `ray` stopped before the parameter `s_in`.
inline bool stopped_before(const StoppedRays* stopped, std::uint32_t ray, double s_in) {
  if (stopped == nullptr) return false;
  const auto it = stopped->at.find(ray);
  return it != stopped->at.end() && s_in > it->second;
}

/// One view's credits under `Metric` (cell_sum) on `cells`, linear indices ascending: each cell's
/// credit by the first of the view's rays (view_rays' order: rows, then columns) that reaches it,
/// the cells credited more than 0 listed (ViewCells::seen: the credits; ViewCells::targets: the
/// cells some ray of the view's image may pass through). The sum of the credits of all cells is
/// view_rays' value at the metric's own pitch without cell counts, up to the order of the
/// additions. `at` holds the cells' indices (GridSpec::unravel). `taken` has a bit per cell of the
/// map, every one set; it is left so. A cell the context's shadows hide from the view's origin
/// (OctantShadows::hides) is credited 0 without a look at its rays, and a ray that blocked_before
/// proves not to reach the cell is not walked: the same credits, bit for bit. ViewCells::targets
/// counts the cells some ray of the view's image may pass through, the hidden ones left out.
///
/// Nor is a ray walked to a cell it enters only past where an occupied cell stopped it, in
/// `known` (the view's rays stopped in earlier calls, or null) or in `found`, where each walk that
/// an occupied cell stops adds its ray: the cell's cube, widened by kCellSpare, is entered after
/// that cell's, by a margin no rounding of the walk's boundaries reaches, so the walk would have
/// ended before it. The same credits, bit for bit, whatever the two hold.
template <typename Metric>
ViewCells view_cell_credits(const MetricContext& ctx, const Frustum& view,
                            std::span<const std::uint32_t> cells, std::span<const Index3> at,
                            std::vector<std::uint64_t>& taken, const StoppedRays* known,
                            StoppedRays& found) {
  static_assert(cell_sum<Metric>(), "the metric's value is not a sum of cell credits");
  const GridSpec& spec = ctx.map.spec();
  const RayImage image(spec, ctx.spacing, ctx.subsample, 1, view);
  const Eigen::Vector3d& o = image.origin;
  const OctantShadows* shadows = ctx.shadows;
  const std::uint8_t open = shadows != nullptr ? shadows->open_octants(o) : 0;
  const std::uint8_t* reach = ctx.reach;
  // NOTE: a stamp that takes no cell but the one listed: every bit set but its own.
  Stamp credit{taken};
  ViewCells out;
  const double half = (0.5 + kCellSpare) * spec.resolution;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const std::uint32_t i = cells[k];
    const Index3& c = at[k];
    // NOTE: most listed cells lie inside the objects, hidden from every side.
    if (shadows != nullptr && shadows->hides(o, open, c)) continue;
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
        const auto ray = static_cast<std::uint32_t>(row) * static_cast<std::uint32_t>(image.cols) +
                         static_cast<std::uint32_t>(col);
        if (stopped_before(known, ray, s_in) || stopped_before(&found, ray, s_in)) continue;
        // NOTE: most rays to a listed cell end on the surface it lies next to.
        if (blocked_before(spec, reach, o, d, c)) continue;
        GridWalk walk(spec, o, to);
        if (!walk.entered()) continue;
        metric.begin_ray();
        ViewGain unused;
        reached = walk_codes(ctx, image, reach, walk, metric, credit, credit, unused, &c).reached;
        // NOTE: a walk that passed the cell on an axis may rest on an occupied cell it has not
        // read yet: it entered it all the same, so the ray stops there.
        if (!reached && spec.contains(walk.cell()) && reach[walk.linear()] == kOccupiedCode) {
          found.at.emplace(ray, walk.t());
        }
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
  return out;
}

/// Every view's credits under `Metric` on `cells` (view_cell_credits); views, and runs of the cells
/// when the views are few, in parallel, each view's list joined in cell order, so the same for any
/// thread count. `stopped`, empty or one per view: the rays each view's earlier calls saw stopped,
/// read by every run and joined by this call's (what they hold changes no credit).
template <typename Metric>
std::vector<ViewCells> all_view_cells(const MetricContext& given, std::span<const Frustum> views,
                                      std::span<const std::uint32_t> cells, int num_threads,
                                      std::span<StoppedRays* const> stopped) {
  // NOTE: the codes the walks read, built here when the context has none; no cell counts.
  MetricContext ctx = given;
  ctx.count_cells = false;
  std::vector<std::uint8_t> codes;
  if (ctx.reach == nullptr) {
    codes =
        reach_codes(ctx.map, ctx.near, ctx.free != nullptr ? *ctx.free : FreeSpace{}, num_threads);
    ctx.reach = codes.data();
  }
  std::vector<ViewCells> out(views.size());
  const std::size_t words = (ctx.map.size() + 63) / 64;
  tbb::enumerable_thread_specific<std::vector<std::uint64_t>> taken(
      [words] { return std::vector<std::uint64_t>(words, ~std::uint64_t{0}); });
  std::vector<Index3> at(cells.size());
  for (std::size_t k = 0; k < cells.size(); ++k) at[k] = ctx.map.spec().unravel(cells[k]);
  // NOTE: at least 16 tasks when the cells allow runs of 256, so that a round of few views keeps
  // both threads busy to its end.
  constexpr std::size_t kTasks = 16, kLeastRun = 256;
  const std::size_t runs =
      std::clamp<std::size_t>((kTasks + views.size() - 1) / views.size(), 1,
                              std::max<std::size_t>(1, cells.size() / kLeastRun));
  const std::size_t run_cells = (cells.size() + runs - 1) / runs;
  std::vector<ViewCells> parts(views.size() * runs);
  std::vector<StoppedRays> found(parts.size());
  run_with_threads(num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, parts.size(), [&](std::size_t task) {
      const std::size_t v = task / runs, from = std::min(cells.size(), task % runs * run_cells);
      const std::size_t n = std::min(cells.size() - from, run_cells);
      parts[task] = view_cell_credits<Metric>(
          ctx, views[v], cells.subspan(from, n), std::span<const Index3>(at).subspan(from, n),
          taken.local(), stopped.empty() ? nullptr : stopped[v], found[task]);
    });
    // NOTE: each view's runs joined in order, the views side by side (the stopped rays' hash
    // inserts were a serial millisecond of a round).
    tbb::parallel_for(std::size_t{0}, views.size(), [&](std::size_t v) {
      for (std::size_t r = 0; r < runs; ++r) {
        ViewCells& part = parts[v * runs + r];
        out[v].cells.insert(out[v].cells.end(), part.cells.begin(), part.cells.end());
        out[v].seen.insert(out[v].seen.end(), part.seen.begin(), part.seen.end());
        out[v].targets += part.targets;
        if (!stopped.empty()) stopped[v]->at.merge(found[v * runs + r].at);
      }
    });
  });
  return out;
}

}  // namespace vantage::detail
