#include "vantage/gain/evaluators/swept.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "vantage/gain/free_space.hpp"
#include "vantage/map/traversal.hpp"
#include "vantage/util/hash.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// What a bound is scaled by so that the estimate's rounding stays below it: a ray's terms are
/// summed over at most a few thousand cells, each rounded by 2^-53 of the sum.
constexpr double kSweptBoundSlack = 1.0 + 1e-9;

/// What one ray credits: sum over the unobserved cells it crosses inside [r_min, r_max] of
/// v * (r1^3 - r0^3), v falling by alpha past each unobserved cell (1 for greedy's alpha), the
/// ray ending in an occupied cell. Cells outside the grid are free. `d` is a unit direction, so
/// the walk's parameter times r_max is the distance.
double ray_credit(const ClassMap& map, const FreeSpace& free, const Eigen::Vector3d& o,
                  const Eigen::Vector3d& d, double r_min, double r_max, double alpha,
                  double epsilon) {
  const GridSpec& spec = map.spec();
  const Eigen::Vector3d to = o + r_max * d;
  GridWalk walk(spec, o, to);
  if (!walk.entered()) return 0.0;
  const double lo_t = r_min / r_max;
  double v = 1.0, credit = 0.0;
  for (;;) {
    const CellState state = map.state(walk.linear());
    if (state == CellState::kOccupied) break;
    if (state == CellState::kFree && !free.empty() && free.cross(walk, spec)) {
      if (!spec.contains(walk.cell())) break;
      continue;
    }
    const double t_leave = std::min(walk.t_exit(), 1.0);
    if (state == CellState::kUnobserved) {
      const double t0 = std::max(walk.t(), lo_t);
      if (t_leave > t0) credit += v * (t_leave * t_leave * t_leave - t0 * t0 * t0);
      v *= alpha;
      if (v < epsilon) break;
    }
    if (walk.at_end()) break;
    walk.advance();
    if (!spec.contains(walk.cell())) break;
  }
  return credit * r_max * r_max * r_max;
}

/// A point in pixel (i, j), jittered by a hash of (i, j): a regular lattice of rays lines up
/// with the grid's and aliases.
Eigen::Vector2d jitter(int i, int j) {
  const std::uint64_t bits =
      mix64((static_cast<std::uint64_t>(j) << 20) ^ static_cast<std::uint64_t>(i));
  return {(static_cast<double>(bits >> 40) + 0.5) * 0x1.0p-24,
          (static_cast<double>((bits >> 16) & 0xffffffu) + 0.5) * 0x1.0p-24};
}

/// Calls `ray(omega, d)` for each pixel of the view's image, row by row: d the unit direction of
/// the ray through a point jittered within the pixel, omega the pixel's solid angle around it.
template <typename Ray>
void for_each_pixel_ray(const Frustum& view, const SweptConfig& config, Ray&& ray) {
  const SensorFov& fov = view.fov();
  const double tan_h = std::tan(fov.h_fov / 2), tan_v = std::tan(fov.v_fov / 2);
  const double pitch = 2.0 * std::max(tan_h, tan_v) / config.rays_across;
  const int nu = std::max(1, static_cast<int>(std::ceil(2.0 * tan_h / pitch)));
  const int nw = std::max(1, static_cast<int>(std::ceil(2.0 * tan_v / pitch)));
  const double du = 2.0 * tan_h / nu, dw = 2.0 * tan_v / nw;
  const Eigen::Matrix3d R = view.T_world_sensor().linear();
  for (int j = 0; j < nw; ++j) {
    for (int i = 0; i < nu; ++i) {
      const Eigen::Vector2d p = jitter(i, j);
      const double u = -tan_h + (i + p.x()) * du, w = -tan_v + (j + p.y()) * dw;
      const double norm2 = 1.0 + u * u + w * w;
      const double omega = du * dw / (norm2 * std::sqrt(norm2));
      ray(omega, Eigen::Vector3d(R * (Eigen::Vector3d(1.0, u, w) / std::sqrt(norm2))));
    }
  }
}

/// One view's estimate [cells].
double view_credit(const ClassMap& map, const FreeSpace& free, const Frustum& view, double alpha,
                   const SweptConfig& config) {
  const SensorFov& fov = view.fov();
  const Eigen::Vector3d o = view.origin();
  double sum = 0.0;
  for_each_pixel_ray(view, config, [&](double omega, const Eigen::Vector3d& d) {
    sum += omega * ray_credit(map, free, o, d, fov.min_range, fov.max_range, alpha, config.epsilon);
  });
  const double h = map.spec().resolution;
  return sum / (3.0 * h * h * h);
}

/// Throws std::invalid_argument for rays across outside [1, 4096].
void check_rays_across(const SweptConfig& config) {
  if (config.rays_across < 1 || config.rays_across > 4096) {
    throw std::invalid_argument(
        cat("swept.rays_across must lie in [1, 4096], got ", config.rays_across));
  }
}

}  // namespace

std::vector<double> swept_view_counts(const ClassMap& map, std::span<const Frustum> views,
                                      GainQuantity quantity, const SweptConfig& config) {
  if (!counts_classes(quantity)) {
    throw std::invalid_argument(
        "swept_view_counts: counts the survival reading's cells or greedy's");
  }
  check_rays_across(config);
  const double alpha = quantity == GainQuantity::kCount ? 1.0 : config.alpha;
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

std::vector<double> swept_view_bounds(std::span<const Frustum> views, double resolution,
                                      const SweptConfig& config) {
  check_rays_across(config);
  if (!(resolution > 0.0)) {
    throw std::invalid_argument(cat("swept_view_bounds: resolution must be > 0, got ", resolution));
  }
  std::vector<double> out(views.size(), 0.0);
  for (std::size_t v = 0; v < views.size(); ++v) {
    const SensorFov& fov = views[v].fov();
    // NOTE: the bound does not depend on the pose: one pass for views of the last one's field.
    if (v > 0 && fov == views[v - 1].fov()) {
      out[v] = out[v - 1];
      continue;
    }
    // NOTE: ray_credit's own terms: at most 1 - (r_min / r_max)^3 of the parameter's cube, times
    // r_max^3.
    const double lo_t = fov.min_range / fov.max_range;
    const double ray = (1.0 - lo_t * lo_t * lo_t) * fov.max_range * fov.max_range * fov.max_range;
    double sum = 0.0;
    for_each_pixel_ray(views[v], config,
                       [&](double omega, const Eigen::Vector3d&) { sum += omega * ray; });
    out[v] = sum / (3.0 * resolution * resolution * resolution) * kSweptBoundSlack;
  }
  return out;
}

}  // namespace vantage
