#include "vantage/gain/view_gain.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>

#include "vantage/gain/exact.hpp"
#include "vantage/gain/fast.hpp"
#include "vantage/gain/methods.hpp"
#include "vantage/gain/metrics.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

// The cheaper evaluation (GainEvaluation::kAuto). The exact mode's work follows the unobserved
// cells in view, times the length of their rays; the fast mode's follows its rays, whatever is
// left unobserved. Both are counted before any ray is cast, so the choice is a function of the
// map state and the views alone: deterministic, and the same for any thread count.

/// Unobserved cells are sampled on every kCostStride-th cell along each axis.
constexpr int kCostStride = 3;
/// Cost of one cell step of the exact mode in units of one ray of the fast mode: 4.4 ns against
/// 2.0 us of CPU, each within 15% over the built-in table tops after 1, 3 and 6 scans. Since the
/// rays got 20% cheaper the measured ratio is 2.2e-3 to 2.7e-3; the states it would decide
/// differently lie within 6% of each other in both modes (BENCHMARK.md, "The built-in scenes").
constexpr double kExactStepPerRay = 2.2e-3;

/// The exact mode's cell steps over all views: per unobserved cell in view, sampled, the L1
/// lattice distance from the sensor's cell, the length of a 6-connected ray; counted once per
/// origin, as the exact mode evaluates a cell once for all views from one origin.
double exact_steps(const GainMap& map, std::span<const Frustum> views) {
  const GridSpec& spec = map.spec();
  const std::vector<std::vector<std::size_t>> groups = views_by_origin(views);
  std::vector<double> per_group(groups.size(), 0.0);
  tbb::parallel_for(std::size_t{0}, groups.size(), [&](std::size_t g) {
    const Index3 origin = spec.lattice_index(views[groups[g].front()].origin());
    CellBox box{spec.dims, Index3(-1, -1, -1)};
    for (const std::size_t v : groups[g]) {
      const CellBox b = cells_under(spec, views[v]);
      if (b.empty()) continue;
      box.lo = box.lo.cwiseMin(b.lo);
      box.hi = box.hi.cwiseMax(b.hi);
    }
    double steps = 0.0;
    Index3 c;
    for (c.z() = box.lo.z(); c.z() <= box.hi.z(); c.z() += kCostStride) {
      for (c.y() = box.lo.y(); c.y() <= box.hi.y(); c.y() += kCostStride) {
        for (c.x() = box.lo.x(); c.x() <= box.hi.x(); c.x() += kCostStride) {
          if (map.value(spec.linear(c)).state != CellState::kUnobserved) continue;
          const Eigen::Vector3d center = spec.center(c);
          const bool in_view = std::any_of(groups[g].begin(), groups[g].end(), [&](std::size_t v) {
            return views[v].contains(center);
          });
          if (in_view) steps += (c - origin).cwiseAbs().sum();  // a 6-connected ray
        }
      }
    }
    per_group[g] = steps * kCostStride * kCostStride * kCostStride;
  });
  double total = 0.0;
  for (const double steps : per_group) total += steps;
  return total;
}

/// The cheaper of the two evaluations on one snapshot.
std::vector<ViewGain> cheapest_view_gains(const GainMap& map, std::span<const Frustum> views,
                                          const GainConfig& config) {
  if (!method_traits(config.method).fast_mode) return exact_view_gains(map, views, config);
  std::vector<ViewGain> gains;
  run_with_threads(config.num_threads, [&] {
    const detail::FastPlan plan = detail::plan_rays(map, views, config);
    if (exact_steps(map, views) * kExactStepPerRay < plan.live_rays()) {
      gains = exact_view_gains(map, views, config);
    } else {
      gains = detail::cast_rays(plan, map, views, config);
    }
  });
  return gains;
}

}  // namespace

constexpr EnumNames<GainEvaluation, 3> kEvaluationNames = {{{GainEvaluation::kExact, "exact"},
                                                            {GainEvaluation::kFast, "fast"},
                                                            {GainEvaluation::kAuto, "auto"}}};

std::string_view to_string(GainEvaluation evaluation) {
  return name_of(evaluation, kEvaluationNames);
}

GainEvaluation parse_gain_evaluation(std::string_view name) {
  return value_named(name, kEvaluationNames, "gain evaluation");
}

void GainConfig::validate() const {
  if (!(alpha > 0.0 && alpha <= 1.0)) {
    throw std::invalid_argument(cat("gain.alpha must lie in (0, 1], got ", alpha));
  }
  if (!(epsilon >= 0.0 && epsilon < 0.5)) {
    throw std::invalid_argument(cat("gain.epsilon must lie in [0, 0.5), got ", epsilon));
  }
  if (!(ray_spacing > 0.0 && ray_spacing <= 1.0)) {
    throw std::invalid_argument(
        cat("gain.ray_spacing must lie in (0, 1] cells, got ", ray_spacing));
  }
  if (num_threads < 0) {
    throw std::invalid_argument(cat("gain.num_threads must be >= 0, got ", num_threads));
  }
}

std::vector<ViewGain> evaluate_views(const OccupancyGrid& grid, std::span<const Frustum> views,
                                     const GainConfig& config) {
  if (is_volumetric_metric(config.method)) return metric_view_gains(grid, views, config);
  switch (config.evaluation) {
    case GainEvaluation::kExact:
      return exact_view_gains(grid, views, config);
    case GainEvaluation::kFast:
      return fast_view_gains(grid, views, config);
    case GainEvaluation::kAuto:
      config.validate();
      return cheapest_view_gains(GainMap(grid, config.num_threads), views, config);
  }
  throw std::invalid_argument("gain.evaluation is not a known evaluation");
}

}  // namespace vantage
