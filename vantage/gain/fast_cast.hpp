#pragma once
/// @file
/// The cast of one fast ray (docs/fast-gain.md "The state a ray carries"): a walk outward from
/// the sensor that carries the model's state, credits each unobserved cell it owns by a replay,
/// and jumps across uniform space. Internal to vantage/gain.

#include <Eigen/Core>
#include <cstddef>
#include <limits>

#include "vantage/gain/fast_layout.hpp"
#include "vantage/gain/fast_replay.hpp"
#include "vantage/gain/model.hpp"
#include "vantage/gain/snapshot.hpp"
#include "vantage/map/traversal.hpp"

namespace vantage::detail {

/// One ray's contribution to each member of its group.
struct RaySum {
  double gain[kMaxGroup] = {};
  double cells[kMaxGroup] = {};
  std::size_t targets[kMaxGroup] = {};

  void add(const RaySum& o, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      gain[i] += o.gain[i];
      cells[i] += o.cells[i];
      targets[i] += o.targets[i];
    }
  }
};

/// The footprint of one pixel in the plane x = 1 of its group's frame, widened to infinity on
/// the border of the image, so that every point in front of the sensor has exactly one owner.
struct Footprint {
  double u_lo, u_hi, v_lo, v_hi;

  Footprint(const RayGroup& rays, int col, int row) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    // NOTE: a shared edge is the same expression for both pixels beside it, so the comparisons
    // in owns() split the points between them exactly.
    u_lo = col == 0 ? -kInf : rays.u0 + col * rays.du;
    u_hi = col == rays.cols - 1 ? kInf : rays.u0 + (col + 1) * rays.du;
    v_lo = row == 0 ? -kInf : rays.v0 + row * rays.du;
    v_hi = row == rays.rows - 1 ? kInf : rays.v0 + (row + 1) * rays.du;
  }

  /// Whether the image of a point holds in this footprint: the point in the group frame is
  /// compared against the footprint scaled to its depth, without a division.
  bool owns(const RayGroup& rays, const Eigen::Vector3d& p_world) const {
    const Eigen::Vector3d p = rays.Rt * (p_world - rays.origin);
    return p.x() > 0.0 && p.y() >= u_lo * p.x() && p.y() < u_hi * p.x() && p.z() >= v_lo * p.x() &&
           p.z() < v_hi * p.x();
  }
};

/// Credits the walk's cell, an unobserved cell the ray owns, to every member that holds it; the
/// replay runs once, for the first. Inlined, like settle_and_jump, so that the ray's state stays in
/// registers in cast_ray's loop.
template <typename CodeT, typename Model>
[[gnu::always_inline]] inline void credit(const CastContext<Model>& cx, const CodeT* codes,
                                          const RayGroup& rays, const Kept* history, int ray_m0,
                                          const GridWalk& walk, const Eigen::Vector3d& c,
                                          RaySum& sum) {
  TargetPrediction g;
  bool replayed = false;
  for (std::size_t k = 0; k < rays.views.size(); ++k) {
    if (!rays.views[k]->contains(c)) continue;
    if (!replayed) {
      g = replay(cx, codes, rays, history, ray_m0, walk.cell, walk.m);
      replayed = true;
    }
    sum.gain[k] += g.gain;
    sum.cells[k] += g.seen;
    ++sum.targets[k];
  }
}

/// Counts an owned unobserved cell that is not credited (its posterior is pinned, so it gains
/// nothing) as seen with visibility `v`, the carrying ray's, by every member that holds it.
inline void see(const RayGroup& rays, const Eigen::Vector3d& c, double v, RaySum& sum) {
  for (std::size_t k = 0; k < rays.views.size(); ++k) {
    if (rays.views[k]->contains(c)) sum.cells[k] += v;
  }
}

/// Counts the cells a jump across uniform unobserved space passed over, from the walk `from` up to
/// the landing cell c_{to_m}, with the steady state's visibility there.
template <typename Model>
void see_jumped(const CastContext<Model>& cx, std::size_t code, const RayGroup& rays,
                const Footprint& footprint, GridWalk from, int to_m, RaySum& sum) {
  const std::vector<RayOdds>& steady = cx.steady[code];
  while (from.advance() && from.m < to_m) {
    const Eigen::Vector3d c = cx.spec->center(from.cell);
    if (footprint.owns(rays, c)) {
      see(rays, c, steady[static_cast<std::size_t>(from.m)].visibility(), sum);
    }
  }
}

/// Casts the ray of pixel (col, row) of a group's image.
template <typename CodeT, typename Model>
RaySum cast_ray(const CastContext<Model>& cx, const CodeT* codes, const RayGroup& rays, int col,
                int row) {
  RaySum sum;
  const GridSpec& spec = *cx.spec;
  const BlockSummary& blocks = *cx.blocks;
  RayPath ray;
  ray.o = rays.origin;
  ray.origin_cell = rays.origin_cell;
  ray.dir = rays.R *
            Eigen::Vector3d(1.0, rays.u0 + (col + 0.5) * rays.du, rays.v0 + (row + 0.5) * rays.du);
  ray.s_out = rays.reach / ray.dir.norm();
  if (!clip_to_grid(spec, ray.o, ray.dir, ray.s_in, ray.s_out) || !(ray.s_in < ray.s_out)) {
    return sum;
  }
  ray.last = cell_at(spec, ray.o + ray.s_out * ray.dir);
  GridWalk walk;
  walk.start(spec, ray.o, ray.dir,
             rays.origin_inside ? rays.origin_cell : cell_at(spec, ray.o + ray.s_in * ray.dir),
             ray.last, rays.origin_cell);
  const int m0 = walk.m;
  const Footprint footprint(rays, col, row);
  const double eps = cx.epsilon;
  std::size_t last_block = std::numeric_limits<std::size_t>::max();
  Kept history[kHistory];
  RayOdds odds;
  double p_prev = cx.tables.p_min;
  if (m0 > 0) odds = cx.tables.outside[static_cast<std::size_t>(m0)];
  for (;;) {
    const auto code_index = static_cast<std::size_t>(codes[walk.linear]);
    const GainMap::Value& code = cx.values[code_index];
    if (walk.m == 0) {
      odds = Model::start(code.p);  // the origin's cell: v_0 = 1, q_0 = p_0
    } else {
      cx.tables.step(odds, walk.m, p_prev, code.p);
    }
    p_prev = code.p;
    history[walk.m & (kHistory - 1)] = {odds, code.p};
    // A pinned cell deep in a uniform region gains nothing: within kSkipMargin blocks of it every
    // cell has its code, so its exact ray's last cells evolve exactly as this ray's did. Nearer a
    // border its own ray may graze known space and be re-armed, so it is replayed.
    const std::size_t block = blocks.index(walk.cell);
    const bool deep = blocks.code[block] == code_index && blocks.radius[block] >= kSkipMargin;
    if (code.state == CellState::kUnobserved) {
      const Eigen::Vector3d c = spec.center(walk.cell);
      if (footprint.owns(rays, c)) {
        if (deep && odds.pinned(eps)) {
          see(rays, c, odds.visibility(), sum);
        } else {
          credit(cx, codes, rays, history, m0, walk, c, sum);
        }
      }
    }
    if (odds.hidden(eps)) break;
    // A uniform region the state has settled in: jump it. The landing cell has the same code,
    // nothing new to credit there; the unobserved cells passed over still count as seen.
    const bool new_block = block != last_block;
    last_block = block;
    if (new_block && blocks.code[block] == code_index &&
        (code.state == CellState::kFree ||
         (code.state == CellState::kUnobserved && odds.pinned(eps)))) {
      const GridWalk from = walk;
      if (settle_and_jump(cx, ray, code_index, m0, odds, history, walk)) {
        if (code.state == CellState::kUnobserved) {
          see_jumped(cx, code_index, rays, footprint, from, walk.m, sum);
        }
        continue;
      }
    }
    if (!walk.advance()) break;
  }
  return sum;
}

}  // namespace vantage::detail
