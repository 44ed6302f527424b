#include "vantage/gain/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "vantage/gain/detail/metric_rays.hpp"
#include "vantage/gain/free_space.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/map/block_census.hpp"
#include "vantage/util/text.hpp"

namespace vantage {

bool is_volumetric_metric(GainMethod method) {
  return method_traits(method).kind == MethodKind::kMetric;
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

namespace {

/// The census of the snapshot's classes, for a map without its grid.
BlockCensus census_of(const GainMap& map) {
  BlockCensus census(map.spec().dims);
  for (std::size_t i = 0; i < map.size(); ++i) {
    const CellState state = map.value(i).state;
    if (state != CellState::kUnobserved) census.move(i, CellState::kUnobserved, state);
  }
  return census;
}

/// The metric's evaluation: by the jumping walk over `free`, or the reference walk when null.
std::vector<ViewGain> evaluate(const GainMap& map, const FreeSpace* free,
                               std::span<const Frustum> views, const GainConfig& config) {
  config.validate();
  if (!is_volumetric_metric(config.method)) {
    throw std::invalid_argument(
        cat("gain.method '", to_string(config.method), "' is not a volumetric metric"));
  }
  const MethodTraits& method = method_traits(config.method);
  const std::vector<float> near =
      method.needs_distances ? occupied_distance(map, kProximityCells) : std::vector<float>{};
  const detail::MetricContext ctx{map, near, config.ray_spacing,
                                  config.evaluation == GainEvaluation::kExact ? 1 : kFastSubsample,
                                  free};
  return method.metric(ctx, views, config.num_threads);
}

}  // namespace

std::vector<ViewGain> metric_view_gains(const GainMap& map, std::span<const Frustum> views,
                                        const GainConfig& config) {
  const FreeSpace free = free_space(census_of(map));
  return evaluate(map, &free, views, config);
}

std::vector<ViewGain> metric_view_gains(const OccupancyGrid& grid, std::span<const Frustum> views,
                                        const GainConfig& config) {
  config.validate();
  const FreeSpace free = free_space(grid.census());
  return evaluate(GainMap(grid, config.num_threads), &free, views, config);
}

std::vector<ViewGain> metric_view_gains_reference(const GainMap& map,
                                                  std::span<const Frustum> views,
                                                  const GainConfig& config) {
  return evaluate(map, nullptr, views, config);
}

}  // namespace vantage
