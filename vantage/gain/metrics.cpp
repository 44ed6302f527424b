#include "vantage/gain/metrics.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "vantage/map/traversal.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

// The definitions, equations and where rpg_ig_active_reconstruction's code differs from the
// paper: docs/model.md, "The field's metrics". Entropies are in bits (the paper's in nats: a
// constant factor, the same ranking).

/// A cell as a metric sees it on its ray.
struct RayCell {
  std::size_t linear;
  const GainMap::Value& value;
  double visibility;  ///< P_v: the product of 1 - p over the ray's cells before this one
  float near;         ///< distance to the nearest occupied cell [cells], +inf beyond D
  bool in_range;      ///< the cell's centre lies at least the sensor's min range away
};

/// Marks cells counted in the current view: one stamp array per thread, one id per view.
struct Stamp {
  std::vector<std::uint32_t>& marks;
  std::uint32_t id;
  /// True the first time a cell is taken in this view.
  bool take(std::size_t i) {
    if (marks[i] == id) return false;
    marks[i] = id;
    return true;
  }
};

bool unknown(const RayCell& c) { return c.value.state == CellState::kUnobserved; }

// Each metric below follows one view's rays: begin_ray(), cell() for every cell the ray crosses
// in order (the last one occupied when the ray ended on one), end_ray(rear_side), where
// rear_side says the ray ended on an occupied cell right behind an unobserved one; value() once
// all rays are cast. Cells are credited once per view (Stamp).

/// Occlusion aware: I_o(x) = P_v(x) I(x), P_v(x_n) = prod_{i<n} (1 - P_o(x_i)) (docs/model.md,
/// eq. M1): every cell's entropy weighted by the chance that it is seen.
struct OcclusionAware {
  double sum = 0.0;
  void begin_ray() {}
  void cell(const RayCell& c, Stamp& s) {
    if (c.in_range && s.take(c.linear)) sum += c.visibility * c.value.entropy;
  }
  void end_ray(bool, Stamp&) {}
  double value(double) const { return sum; }
};

/// Unobserved voxel: I_u(x) = 1 if x is unobserved, else 0 (eq. M2): the unobserved cells the
/// rays reach.
struct UnobservedVoxel {
  double sum = 0.0;
  void begin_ray() {}
  void cell(const RayCell& c, Stamp& s) {
    if (c.in_range && unknown(c) && s.take(c.linear)) sum += 1.0;
  }
  void end_ray(bool, Stamp&) {}
  double value(double) const { return sum; }
};

/// Rear side voxel: I_b(x) = 1 if x is an occupied cell that its ray reaches straight from an
/// unobserved cell, a rear side of a surface seen before (eq. M3), else 0.
struct RearSideVoxel {
  double sum = 0.0;
  bool previous_unknown = false;
  void begin_ray() { previous_unknown = false; }
  void cell(const RayCell& c, Stamp& s) {
    if (c.value.state == CellState::kOccupied && previous_unknown && c.in_range &&
        s.take(c.linear)) {
      sum += 1.0;
    }
    previous_unknown = unknown(c);
  }
  void end_ray(bool, Stamp&) {}
  double value(double) const { return sum; }
};

/// Rear side entropy: I_n(x) = P_v(x) I(x) for the unobserved cells on rays that end on a rear
/// side, else 0 (eq. M4).
struct RearSideEntropy {
  double sum = 0.0;
  std::vector<std::pair<std::size_t, double>> pending;  // this ray's unobserved cells, P_v I
  void begin_ray() { pending.clear(); }
  void cell(const RayCell& c, Stamp&) {
    if (c.in_range && unknown(c)) pending.emplace_back(c.linear, c.visibility * c.value.entropy);
  }
  void end_ray(bool rear_side, Stamp& s) {
    if (!rear_side) return;
    for (const auto& [linear, gain] : pending) {
      if (s.take(linear)) sum += gain;
    }
  }
  double value(double) const { return sum; }
};

/// Proximity count: I_p(x) = D - d(x) for an unobserved cell x within distance d(x) <= D of an
/// occupied cell, else 0 (eq. M5): unobserved cells near a surface, the nearer the more.
struct ProximityCount {
  double sum = 0.0;
  void begin_ray() {}
  void cell(const RayCell& c, Stamp& s) {
    if (c.in_range && unknown(c) && c.near <= kProximityCells && s.take(c.linear)) {
      sum += kProximityCells - c.near;
    }
  }
  void end_ray(bool, Stamp&) {}
  double value(double) const { return sum; }
};

/// Average entropy (Kriegel et al. 2015): G = sum_{x in X} I(x) / |X| over the set X of cells
/// the rays traverse (eq. M6).
struct AverageEntropy {
  double sum = 0.0, count = 0.0;
  void begin_ray() {}
  void cell(const RayCell& c, Stamp& s) {
    if (c.in_range && s.take(c.linear)) {
      sum += c.value.entropy;
      count += 1.0;
    }
  }
  void end_ray(bool, Stamp&) {}
  double value(double) const { return count > 0.0 ? sum / count : 0.0; }
};

/// Vasquez-Gomez's area factor (eq. M7): each ray is registered once, at its first cell that is
/// occupied (counted when seen from free space, its front) or an "occplane" cell (unobserved,
/// within D of an occupied cell); rays that register neither are unmarked. With x_o and x_p the
/// fractions of all the view's rays registered occupied and occplane,
/// G = f(x_o; 0.2) + f(x_p; 0.8).
struct AreaFactor {
  double occupied = 0.0, occplane = 0.0;
  bool previous_free = true, registered = false;
  void begin_ray() {
    previous_free = true;  // the cells outside the grid are free (docs/model.md)
    registered = false;
  }
  void cell(const RayCell& c, Stamp&) {
    if (registered || !c.in_range) {
      previous_free = c.value.state == CellState::kFree;
      return;
    }
    if (unknown(c) && c.near <= kProximityCells) {
      occplane += 1.0;
      registered = true;
    } else if (c.value.state == CellState::kOccupied) {
      if (previous_free) occupied += 1.0;
      registered = true;
    }
    previous_free = c.value.state == CellState::kFree;
  }
  void end_ray(bool, Stamp&) {}
  double value(double rays) const {
    if (rays <= 0.0) return 0.0;
    return area_factor(occupied / rays, kAreaOccupied) +
           area_factor(occplane / rays, kAreaOccplane);
  }
};

/// What the metrics of one evaluation share.
struct Context {
  const GainMap& map;
  const std::vector<float>& near;  // empty when the metric needs no distances
  double spacing;                  // ray pitch at the farthest cell in view [cells]
  int subsample;                   // cast every subsample-th ray along each image axis
};

/// Casts one view's rays and feeds them to `metric`; returns the metric's value and the count of
/// unobserved cells reached.
template <typename Metric>
ViewGain cast_view(const Context& ctx, const Frustum& view, Metric& metric, Stamp& credit,
                   Stamp& seen) {
  const GridSpec& spec = ctx.map.spec();
  const SensorFov& fov = view.fov();
  const Eigen::Vector3d o = view.origin();
  const Eigen::Matrix3d R = view.T_world_sensor().linear();
  // The pitch: neighbouring rays `spacing` cells apart at the farthest corner of the grid.
  double depth = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p((corner & 1) ? spec.max_corner().x() : spec.origin.x(),
                            (corner & 2) ? spec.max_corner().y() : spec.origin.y(),
                            (corner & 4) ? spec.max_corner().z() : spec.origin.z());
    depth = std::max(depth, (p - o).norm());
  }
  depth = std::clamp(depth, spec.resolution, fov.max_range);
  const double du = ctx.spacing * spec.resolution / depth;
  const double tan_h = std::tan(fov.h_fov / 2.0), tan_v = std::tan(fov.v_fov / 2.0);
  const int cols = std::max(1, static_cast<int>(std::ceil(2.0 * tan_h / du)));
  const int rows = std::max(1, static_cast<int>(std::ceil(2.0 * tan_v / du)));
  const double su = 2.0 * tan_h / cols, sv = 2.0 * tan_v / rows;
  const double min_r2 = fov.min_range * fov.min_range;
  const float far = std::numeric_limits<float>::infinity();

  ViewGain result;
  double rays = 0.0;
  const int first = ctx.subsample / 2;
  for (int row = first; row < rows; row += ctx.subsample) {
    for (int col = first; col < cols; col += ctx.subsample) {
      rays += 1.0;
      const Eigen::Vector3d dir =
          (R * Eigen::Vector3d(1.0, -tan_h + (col + 0.5) * su, -tan_v + (row + 0.5) * sv))
              .normalized();
      metric.begin_ray();
      double visibility = 1.0;
      bool previous_unknown = false, rear_side = false;
      traverse(spec, o, o + fov.max_range * dir, [&](const Index3& cell, std::size_t linear, int) {
        const GainMap::Value& v = ctx.map.value(linear);
        const bool in_range = (spec.center(cell) - o).squaredNorm() >= min_r2;
        const RayCell c{linear, v, visibility, ctx.near.empty() ? far : ctx.near[linear], in_range};
        metric.cell(c, credit);
        if (in_range && unknown(c) && seen.take(linear)) result.cells += 1.0;
        if (v.state == CellState::kOccupied) {
          rear_side = previous_unknown;
          return false;  // the ray ends on its first occupied cell
        }
        previous_unknown = unknown(c);
        visibility *= 1.0 - v.p;  // eq. M1: P_v(x_{n+1}) = P_v(x_n) (1 - P_o(x_n))
        return true;
      });
      metric.end_ray(rear_side, credit);
    }
  }
  result.gain = metric.value(rays);
  result.targets = static_cast<std::size_t>(result.cells);
  return result;
}

/// Every view's value under `Metric`; views in parallel, each view's rays in order on one thread,
/// so the result does not depend on threads.
template <typename Metric>
std::vector<ViewGain> all_views(const Context& ctx, std::span<const Frustum> views,
                                int num_threads) {
  std::vector<ViewGain> gains(views.size());
  struct Marks {
    std::vector<std::uint32_t> credit, seen;
  };
  const std::size_t cells = ctx.map.size();
  tbb::enumerable_thread_specific<Marks> marks([cells] {
    return Marks{std::vector<std::uint32_t>(cells, 0), std::vector<std::uint32_t>(cells, 0)};
  });
  run_with_threads(num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, views.size(), [&](std::size_t v) {
      Marks& m = marks.local();
      const auto id = static_cast<std::uint32_t>(v + 1);
      Stamp credit{m.credit, id}, seen{m.seen, id};
      Metric metric;
      gains[v] = cast_view(ctx, views[v], metric, credit, seen);
    });
  });
  return gains;
}

bool needs_distances(GainMethod method) {
  return method == GainMethod::kProximityCount || method == GainMethod::kAreaFactor;
}

}  // namespace

bool is_volumetric_metric(GainMethod method) {
  switch (method) {
    case GainMethod::kOcclusionAware:
    case GainMethod::kUnobservedVoxel:
    case GainMethod::kRearSideVoxel:
    case GainMethod::kRearSideEntropy:
    case GainMethod::kProximityCount:
    case GainMethod::kAverageEntropy:
    case GainMethod::kAreaFactor:
      return true;
    case GainMethod::kProbabilistic:
    case GainMethod::kSurvival:
    case GainMethod::kGreedy:
      return false;
  }

  return false;
}

void require_model_method(const GainConfig& config, std::string_view who) {
  if (is_volumetric_metric(config.method)) {
    throw std::invalid_argument(cat(who, ": ", to_string(config.method),
                                    " is a volumetric metric; evaluate it with evaluate_views"));
  }
}

double area_factor(double x, double alpha) {
  if (x <= alpha) {
    const double a2 = alpha * alpha;
    return (-2.0 / (a2 * alpha)) * x * x * x + (3.0 / a2) * x * x;
  }
  const double m = alpha - 1.0, m3 = m * m * m;
  return (-2.0 * x * x * x + 3.0 * (alpha + 1.0) * x * x - 6.0 * alpha * x + 3.0 * alpha - 1.0) /
         m3;
}

std::vector<float> occupied_distance(const GainMap& map, double radius) {
  const GridSpec& spec = map.spec();
  std::vector<float> near(map.size(), std::numeric_limits<float>::infinity());
  // NOTE: each occupied cell stamps the ball of `radius` around it; the minimum does not depend
  // on the order, and occupied cells are few next to the rest.
  const int r = static_cast<int>(std::floor(radius));
  struct Offset {
    Index3 d;
    float distance;
  };
  std::vector<Offset> ball;
  for (int z = -r; z <= r; ++z) {
    for (int y = -r; y <= r; ++y) {
      for (int x = -r; x <= r; ++x) {
        const double d = std::sqrt(static_cast<double>(x * x + y * y + z * z));
        if (d <= radius) ball.push_back({Index3(x, y, z), static_cast<float>(d)});
      }
    }
  }
  Index3 c;
  for (c.z() = 0; c.z() < spec.dims.z(); ++c.z()) {
    for (c.y() = 0; c.y() < spec.dims.y(); ++c.y()) {
      for (c.x() = 0; c.x() < spec.dims.x(); ++c.x()) {
        if (map.value(spec.linear(c)).state != CellState::kOccupied) continue;
        for (const Offset& o : ball) {
          const Index3 n = c + o.d;
          if (!spec.contains(n)) continue;
          float& slot = near[spec.linear(n)];
          slot = std::min(slot, o.distance);
        }
      }
    }
  }
  return near;
}

std::vector<ViewGain> metric_view_gains(const GainMap& map, std::span<const Frustum> views,
                                        const GainConfig& config) {
  config.validate();
  if (!is_volumetric_metric(config.method)) {
    throw std::invalid_argument(
        cat("gain.method '", to_string(config.method), "' is not a volumetric metric"));
  }
  const std::vector<float> near = needs_distances(config.method)
                                      ? occupied_distance(map, kProximityCells)
                                      : std::vector<float>{};
  const Context ctx{map, near, config.ray_spacing,
                    config.evaluation == GainEvaluation::kExact ? 1 : kFastSubsample};
  switch (config.method) {
    case GainMethod::kOcclusionAware:
      return all_views<OcclusionAware>(ctx, views, config.num_threads);
    case GainMethod::kUnobservedVoxel:
      return all_views<UnobservedVoxel>(ctx, views, config.num_threads);
    case GainMethod::kRearSideVoxel:
      return all_views<RearSideVoxel>(ctx, views, config.num_threads);
    case GainMethod::kRearSideEntropy:
      return all_views<RearSideEntropy>(ctx, views, config.num_threads);
    case GainMethod::kProximityCount:
      return all_views<ProximityCount>(ctx, views, config.num_threads);
    case GainMethod::kAverageEntropy:
      return all_views<AverageEntropy>(ctx, views, config.num_threads);
    case GainMethod::kAreaFactor:
      return all_views<AreaFactor>(ctx, views, config.num_threads);
    case GainMethod::kProbabilistic:
    case GainMethod::kSurvival:
    case GainMethod::kGreedy:
      break;
  }
  return {};
}

std::vector<ViewGain> metric_view_gains(const OccupancyGrid& grid, std::span<const Frustum> views,
                                        const GainConfig& config) {
  config.validate();
  return metric_view_gains(GainMap(grid, config.num_threads), views, config);
}

}  // namespace vantage
