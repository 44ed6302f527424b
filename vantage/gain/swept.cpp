#include "vantage/gain/swept.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "vantage/gain/free_space.hpp"
#include "vantage/map/traversal.hpp"
#include "vantage/util/hash.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// What one ray credits: sum over the unobserved cells it crosses inside [r_min, r_max] of
/// v * (r1^3 - r0^3), v falling by alpha past each unobserved cell (1 for greedy's alpha), the
/// ray ending in an occupied cell. Cells outside the grid are free. Amanatides-Woo in the ray's
/// distance.
double ray_credit(const ClassMap& map, const FreeSpace& free, const Eigen::Vector3d& o,
                  const Eigen::Vector3d& d, double r_min, double r_max, double alpha,
                  double epsilon) {
  const GridSpec& spec = map.spec();
  double s_in = 0.0, s_out = r_max;
  if (!clip_to_grid(spec, o, d, s_in, s_out) || !(s_in < s_out)) return 0.0;
  const double h = spec.resolution;
  const Eigen::Vector3d p = o + s_in * d;
  Index3 cell = spec.lattice_index(p).cwiseMax(Index3::Zero()).cwiseMin(spec.dims - Index3::Ones());
  int step[3];
  double t_next[3], t_delta[3];
  int octant = 0;
  for (int a = 0; a < 3; ++a) {
    step[a] = d[a] > 0.0 ? 1 : (d[a] < 0.0 ? -1 : 0);
    if (step[a] > 0) octant |= 1 << a;  // FreeSpace's octant (an axis not moved on: either)
    t_delta[a] = step[a] == 0 ? std::numeric_limits<double>::infinity() : h / std::abs(d[a]);
  }
  // The next boundary on each axis from the cell the ray is in.
  const auto boundaries = [&] {
    for (int a = 0; a < 3; ++a) {
      t_next[a] = step[a] == 0
                      ? std::numeric_limits<double>::infinity()
                      : (spec.origin[a] + (cell[a] + (step[a] > 0 ? 1 : 0)) * h - o[a]) / d[a];
    }
  };
  boundaries();
  const std::ptrdiff_t stride[3] = {1, spec.dims.x(),
                                    static_cast<std::ptrdiff_t>(spec.dims.x()) * spec.dims.y()};
  std::ptrdiff_t linear = static_cast<std::ptrdiff_t>(spec.linear(cell));
  double v = 1.0, credit = 0.0, t = s_in;
  while (t < s_out) {
    const CellState state = map.state(static_cast<std::size_t>(linear));
    if (state == CellState::kOccupied) break;
    if (state == CellState::kFree && !free.empty()) {
      if (const int e = free.extent_at(octant, cell); e > 0) {
        // Out of the free cube in one step, into the cell past the face it leaves by.
        Index3 lo, hi;
        FreeSpace::cube(cell, octant, e, spec.dims, lo, hi);
        int exit = 0;
        double t_exit = std::numeric_limits<double>::infinity();
        for (int a = 0; a < 3; ++a) {
          if (step[a] == 0) continue;
          const double face = spec.origin[a] + (step[a] > 0 ? hi[a] + 1 : lo[a]) * h;
          const double ta = (face - o[a]) / d[a];
          if (ta < t_exit) {
            t_exit = ta;
            exit = a;
          }
        }
        if (!(t_exit < s_out)) break;
        for (int a = 0; a < 3; ++a) {
          cell[a] = a == exit ? (step[a] > 0 ? hi[a] + 1 : lo[a] - 1)
                              : std::clamp(static_cast<int>(std::floor(
                                               (o[a] + t_exit * d[a] - spec.origin[a]) / h)),
                                           lo[a], hi[a]);
        }
        if (!spec.contains(cell)) break;
        linear = static_cast<std::ptrdiff_t>(spec.linear(cell));
        boundaries();
        t = std::max(t, t_exit);
        continue;
      }
    }
    // NOTE: a branch per axis with constant indices, not an indexed select: the walk's state then
    // stays in registers.
    const auto leave_along = [&]<int A>() {
      const double t_leave = std::min(t_next[A], s_out);
      if (state == CellState::kUnobserved) {
        const double lo = std::max(t, r_min);
        if (t_leave > lo) credit += v * (t_leave * t_leave * t_leave - lo * lo * lo);
        v *= alpha;
        if (v < epsilon) return false;
      }
      t = std::max(t, t_leave);
      cell[A] += step[A];
      if (cell[A] < 0 || cell[A] >= spec.dims[A]) return false;
      linear += step[A] * stride[A];
      t_next[A] += t_delta[A];
      return true;
    };
    const bool on = t_next[0] < t_next[1]
                        ? (t_next[0] < t_next[2] ? leave_along.template operator()<0>()
                                                 : leave_along.template operator()<2>())
                        : (t_next[1] < t_next[2] ? leave_along.template operator()<1>()
                                                 : leave_along.template operator()<2>());
    if (!on) break;
  }
  return credit;
}

/// A point in pixel (i, j), jittered by a hash of (i, j): a regular lattice of rays lines up
/// with the grid's and aliases.
Eigen::Vector2d jitter(int i, int j) {
  const std::uint64_t bits =
      mix64((static_cast<std::uint64_t>(j) << 20) ^ static_cast<std::uint64_t>(i));
  return {(static_cast<double>(bits >> 40) + 0.5) * 0x1.0p-24,
          (static_cast<double>((bits >> 16) & 0xffffffu) + 0.5) * 0x1.0p-24};
}

/// One view's estimate [cells].
double view_credit(const ClassMap& map, const FreeSpace& free, const Frustum& view, double alpha,
                   const SweptConfig& config) {
  const SensorFov& fov = view.fov();
  const double tan_h = std::tan(fov.h_fov / 2), tan_v = std::tan(fov.v_fov / 2);
  const double pitch = 2.0 * std::max(tan_h, tan_v) / config.rays_across;
  const int nu = std::max(1, static_cast<int>(std::ceil(2.0 * tan_h / pitch)));
  const int nw = std::max(1, static_cast<int>(std::ceil(2.0 * tan_v / pitch)));
  const double du = 2.0 * tan_h / nu, dw = 2.0 * tan_v / nw;
  const Eigen::Matrix3d R = view.T_world_sensor().linear();
  const Eigen::Vector3d o = view.origin();
  // The ray through image point (u, w), u and w in pixels; its credit weighted by the solid
  // angle of a pixel around it.
  const auto cast = [&](double u_px, double w_px) {
    const double u = -tan_h + u_px * du, w = -tan_v + w_px * dw;
    const double norm2 = 1.0 + u * u + w * w;
    const double omega = du * dw / (norm2 * std::sqrt(norm2));
    const Eigen::Vector3d d = R * (Eigen::Vector3d(1.0, u, w) / std::sqrt(norm2));
    return omega * ray_credit(map, free, o, d, fov.min_range, fov.max_range, alpha, config.epsilon);
  };
  double sum = 0.0;
  for (int j = 0; j < nw; ++j) {
    for (int i = 0; i < nu; ++i) {
      const Eigen::Vector2d p = jitter(i, j);
      sum += cast(i + p.x(), j + p.y());
    }
  }
  const double h = map.spec().resolution;
  return sum / (3.0 * h * h * h);
}

}  // namespace

std::vector<double> swept_view_counts(const ClassMap& map, std::span<const Frustum> views,
                                      CountRule rule, const SweptConfig& config) {
  if (config.rays_across < 1 || config.rays_across > 4096) {
    throw std::invalid_argument(
        cat("swept.rays_across must lie in [1, 4096], got ", config.rays_across));
  }
  const double alpha = rule == CountRule::kGreedy ? 1.0 : config.alpha;
  if (!(alpha > 0.0 && alpha <= 1.0)) {
    throw std::invalid_argument(cat("swept.alpha must lie in (0, 1], got ", alpha));
  }
  std::vector<double> out(views.size(), 0.0);
  const FreeSpace none;
  const FreeSpace& free = config.skip_free ? map.free_space() : none;
  run_with_threads(config.num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, views.size(), [&](std::size_t v) {
      out[v] = view_credit(map, free, views[v], alpha, config);
    });
  });
  return out;
}

}  // namespace vantage
