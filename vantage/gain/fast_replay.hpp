#pragma once
/// @file
/// What a fast ray does besides stepping (docs/fast-gain.md): the replay of the exact ray over
/// the last cells before a credited cell, and the jump across uniform space. Internal to
/// vantage/gain.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "vantage/gain/fast_layout.hpp"
#include "vantage/gain/model.hpp"
#include "vantage/gain/ray_model.hpp"
#include "vantage/gain/snapshot.hpp"
#include "vantage/map/traversal.hpp"

namespace vantage::detail {

/// Cells of the exact ray replayed before a credited cell (docs/fast-gain.md).
constexpr int kReplayCells = 8;
/// A pinned cell is left uncredited, and a pinned ray jumps, only this many blocks inside a
/// uniform region: kSkipMargin * kBlock >= kReplayCells keeps every replay window inside it.
constexpr int kSkipMargin = 4;
static_assert(kSkipMargin * BlockSummary::kBlock >= kReplayCells);
/// States kept along a ray for the replays, a power of two above kReplayCells.
constexpr int kHistory = 16;
/// A ray jumps a uniform region only once its state lies this close to the region's steady state.
constexpr double kSteadyTolerance = 1e-5;

/// Everything the rays of one fast evaluation share.
template <typename Model>
struct CastContext {
  const GridSpec* spec = nullptr;
  const GainMap::Value* values = nullptr;  ///< per code
  const BlockSummary* blocks = nullptr;
  RayTables<Model> tables;
  std::vector<std::vector<RayOdds>> steady;  ///< per code, the state after m + 1 cells of it
  double epsilon = 0.0;
};

/// A state along the carrying ray, kept for the replays.
struct Kept {
  RayOdds odds;
  double p;  ///< occupancy of the cell
};

/// The cell that holds p, pulled onto the grid.
inline Index3 cell_at(const GridSpec& spec, const Eigen::Vector3d& p) {
  return spec.lattice_index(p).cwiseMax(Index3::Zero()).cwiseMin(spec.dims - Index3::Ones());
}

/// entropy_bits, by its series about 1/2 where most replayed cells lie (error below 1e-13 there):
/// H(1/2 + x) = 1 - (1 / ln 2) sum_n (2x)^2n / (2n (2n - 1)).
inline double entropy_near_half(double q) {
  const double y = 4.0 * (q - 0.5) * (q - 0.5);  // (2x)^2
  if (y > 1e-4) return entropy_bits(q);
  return 1.0 - (y / 2.0 + y * y / 12.0 + y * y * y / 30.0) / std::numbers::ln2;
}

/// The gain and visibility of a credited cell: the exact ray to its centre, replayed over its last
/// cells from the state the carrying ray had there (docs/fast-gain.md). The replay ends on the
/// target, so v_M is at hand.
template <typename CodeT, typename Model>
TargetPrediction replay(const CastContext<Model>& cx, const CodeT* codes, const RayGroup& rays,
                        const Kept* history, int ray_m0, const Index3& target, int m_target) {
  const GridSpec& spec = *cx.spec;
  const Eigen::Vector3d c = spec.center(target);
  const Eigen::Vector3d delta = c - rays.origin;
  const double cells = delta.cwiseAbs().sum() / spec.resolution;
  double s_from = m_target <= kReplayCells ? 0.0 : std::max(0.0, 1.0 - kReplayCells / cells);
  bool from_outside = false;
  if (!spec.contains(spec.lattice_index(rays.origin + s_from * delta))) {
    // The window starts before the grid: the cells there are free, a table lookup.
    double s_in = 0.0, s_out = 1.0;
    clip_to_grid(spec, rays.origin, delta, s_in, s_out);
    s_from = std::max(s_from, s_in);
    from_outside = true;
  }
  GridWalk walk;
  walk.start(spec, rays.origin, delta, cell_at(spec, rays.origin + s_from * delta), target,
             rays.origin_cell);
  RayOdds odds;
  double p_prev = cx.tables.p_min;
  bool first = walk.m == 0;
  if (!first) {
    const int before = walk.m - 1;
    if (from_outside || before < ray_m0 || m_target - before >= kHistory) {
      odds = cx.tables.outside[static_cast<std::size_t>(walk.m)];
    } else {
      const Kept& kept = history[before & (kHistory - 1)];
      odds = kept.odds;
      p_prev = kept.p;
    }
  }
  const GainMap::Value* code = nullptr;
  for (;;) {
    code = &cx.values[codes[walk.linear]];
    if (first) {
      odds = Model::start(code->p);  // the origin's cell
      first = false;
    } else {
      cx.tables.step(odds, walk.m, p_prev, code->p);
    }
    p_prev = code->p;
    if (!walk.advance()) break;
  }
  return {code->entropy - entropy_near_half(odds.posterior()), odds.visibility()};  // eq. (4)
}

/// One ray's line through the grid: o + s * dir for s in [s_in, s_out], ending in `last`.
struct RayPath {
  Eigen::Vector3d o, dir;
  double s_in = 0.0, s_out = 0.0;
  Index3 last, origin_cell;
};

/// Moves `walk` to the last cell along the ray inside the cube of uniform blocks around its
/// cell, shrunk by `margin` blocks, when that skips at least two cells.
inline bool jump_uniform(const GridSpec& spec, const BlockSummary& blocks, const RayPath& ray,
                         int margin, GridWalk& walk) {
  constexpr int kBlock = BlockSummary::kBlock;
  const std::size_t block = blocks.index(walk.cell);
  const int r = blocks.radius[block] - margin;
  if (r < 0) return false;
  double s_exit = ray.s_out;
  for (int a = 0; a < 3; ++a) {
    if (ray.dir[a] == 0.0) continue;
    const int b = (walk.cell[a] >> BlockSummary::kShift) + (ray.dir[a] > 0.0 ? r + 1 : -r);
    const double plane = spec.origin[a] + std::clamp(b * kBlock, 0, spec.dims[a]) * spec.resolution;
    s_exit = std::min(s_exit, (plane - ray.o[a]) / ray.dir[a]);
  }
  const double s_land = s_exit - 1e-9 * (s_exit - ray.s_in + 1.0);
  Index3 land = cell_at(spec, ray.o + s_land * ray.dir);
  // Stay within the uniform cube and never step back.
  for (int a = 0; a < 3; ++a) {
    land[a] = walk.step(a) > 0 ? std::clamp(land[a], walk.cell[a], ray.last[a])
                               : std::clamp(land[a], ray.last[a], walk.cell[a]);
  }
  if ((land - ray.origin_cell).cwiseAbs().sum() <= walk.m + 1) return false;
  walk.start(spec, ray.o, ray.dir, land, ray.last, ray.origin_cell);
  return true;
}

/// A uniform region the state has settled in predicts nothing new until it ends: when the state
/// in the walk's cell (of code `code`) lies within kSteadyTolerance of the region's steady state,
/// jumps to the region's last cell along the ray, with the state the table holds there, and
/// refills the history from the table. True when it jumped.
template <typename Model>
[[gnu::always_inline]] inline bool settle_and_jump(const CastContext<Model>& cx, const RayPath& ray,
                                                   std::size_t code, int ray_m0, RayOdds& odds,
                                                   Kept* history, GridWalk& walk) {
  const GainMap::Value& value = cx.values[code];
  const auto& steady = cx.steady[code];
  // |v - v_f| and |q - q_f| below the tolerance; f sums to 1 in both pairs.
  const RayOdds& f = steady[static_cast<std::size_t>(walk.m)];
  const bool settled =
      std::abs(odds.n * f.d - odds.d * f.n) < kSteadyTolerance * (odds.n + odds.d) &&
      std::abs(odds.a * f.b - odds.b * f.a) < kSteadyTolerance * (odds.a + odds.b);
  if (!settled || !jump_uniform(*cx.spec, *cx.blocks, ray,
                                value.state == CellState::kFree ? 0 : kSkipMargin, walk)) {
    return false;
  }
  odds = steady[static_cast<std::size_t>(walk.m)];
  for (int k = 0; k < kHistory && walk.m - k >= ray_m0; ++k) {
    const int m = walk.m - k;
    history[m & (kHistory - 1)] = {steady[static_cast<std::size_t>(m)], value.p};
  }
  return true;
}

}  // namespace vantage::detail
