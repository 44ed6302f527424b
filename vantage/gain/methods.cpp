#include "vantage/gain/methods.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "vantage/gain/models/metric_cells.hpp"
#include "vantage/gain/models/metric_rays.hpp"
#include "vantage/gain/models/metrics/area_factor.hpp"
#include "vantage/gain/models/metrics/average_entropy.hpp"
#include "vantage/gain/models/metrics/occlusion_aware.hpp"
#include "vantage/gain/models/metrics/proximity_count.hpp"
#include "vantage/gain/models/metrics/rear_side_entropy.hpp"
#include "vantage/gain/models/metrics/rear_side_voxel.hpp"
#include "vantage/gain/models/metrics/surface.hpp"
#include "vantage/gain/models/metrics/unobserved_voxel.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

using detail::all_view_cells;
using detail::all_views;

constexpr MethodTraits target_model(GainMethod method, std::string_view name, TargetRay ray,
                                    bool has_objective, bool counts) {
  return {method, name, MethodKind::kTargetModel, ray, has_objective, counts, false, nullptr};
}

/// A metric's row, what it asks of the evaluation read off its type (models/metric_rays.hpp).
template <typename Metric>
constexpr MethodTraits metric(GainMethod method, std::string_view name,
                              bool needs_distances = false) {
  MetricCellsFn cells = nullptr;
  if constexpr (detail::cell_sum<Metric>()) cells = &all_view_cells<Metric>;
  return {method,
          name,
          MethodKind::kMetric,
          TargetRay::kNone,
          false,
          false,
          needs_distances,
          &all_views<Metric>,
          cells,
          detail::free_dims<Metric>(),
          detail::quiet_cells<Metric>() == detail::QuietCells::kFar};
}

// NOTE: the rows' order is the order names are listed in messages.
constexpr std::array kMethods = {
    //           method                        name             ray  objective counts
    target_model(GainMethod::kProbabilistic, "probabilistic", TargetRay::kPaper, true, false),
    target_model(GainMethod::kSurvival, "survival", TargetRay::kSurvival, true, false),
    target_model(GainMethod::kGreedy, "greedy", TargetRay::kUnblocked, false, true),
    metric<OcclusionAware>(GainMethod::kOcclusionAware, "occlusion-aware"),
    metric<UnobservedVoxel>(GainMethod::kUnobservedVoxel, "unobserved-voxel"),
    metric<RearSideVoxel>(GainMethod::kRearSideVoxel, "rear-side-voxel"),
    metric<RearSideEntropy>(GainMethod::kRearSideEntropy, "rear-side-entropy"),
    metric<ProximityCount>(GainMethod::kProximityCount, "proximity-count", true),
    metric<AverageEntropy>(GainMethod::kAverageEntropy, "average-entropy"),
    metric<AreaFactor>(GainMethod::kAreaFactor, "area-factor", true),
    metric<Surface>(GainMethod::kSurface, "surface", true),
};

}  // namespace

const MethodTraits& method_traits(GainMethod method) {
  const auto it = std::find_if(kMethods.begin(), kMethods.end(),
                               [&](const MethodTraits& t) { return t.method == method; });
  if (it == kMethods.end()) {
    throw std::invalid_argument(
        cat("gain method ", static_cast<int>(method), " is not registered"));
  }
  return *it;
}

std::span<const MethodTraits> gain_methods() { return kMethods; }

std::optional<GainMethod> find_gain_method(std::string_view name) {
  for (const MethodTraits& t : kMethods) {
    if (t.name == name) return t.method;
  }
  return std::nullopt;
}

std::string_view to_string(GainMethod method) { return method_traits(method).name; }

GainMethod parse_gain_method(std::string_view name) {
  if (const std::optional<GainMethod> method = find_gain_method(name)) return *method;
  std::string expected;
  for (std::size_t i = 0; i < kMethods.size(); ++i) {
    expected += cat(i == 0 ? "" : (i + 1 == kMethods.size() ? " or " : ", "), kMethods[i].name);
  }
  throw std::invalid_argument(cat("unknown gain method '", name, "' (expected ", expected, ")"));
}

bool is_volumetric_metric(GainMethod method) {
  return method_traits(method).kind == MethodKind::kMetric;
}

void require_model_method(const GainConfig& config, std::string_view who) {
  if (is_volumetric_metric(config.method)) {
    throw std::invalid_argument(cat(who, ": ", to_string(config.method),
                                    " is a volumetric metric; evaluate it with evaluate_views"));
  }
}

}  // namespace vantage
