#include "vantage/gain/methods.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "vantage/gain/models/metric_bands.hpp"
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

/// A target model's row: its ray, and what it computes ranked by bits and by cells.
constexpr MethodTraits target_model(GainMethod method, std::string_view name, TargetRay ray,
                                    GainQuantity by_bits, GainQuantity by_cells) {
  return {method, name, MethodKind::kTargetModel, ray, by_bits, by_cells, false, nullptr};
}

/// What a metric's row says beside what its type does (models/metric_type.hpp).
struct MetricRow {
  bool needs_distances = false;  ///< MethodTraits::needs_distances
  std::span<const MetricRound> race_rounds = {};
};

/// A metric's row, what it asks of the evaluation read off its type (models/metric_type.hpp).
template <typename Metric>
constexpr MethodTraits metric(GainMethod method, std::string_view name, MetricRow row = {}) {
  MetricCellsFn cells = nullptr;
  MetricFn rays = &all_views<Metric>;
  if constexpr (detail::cell_sum<Metric>()) {
    cells = &all_view_cells<Metric>;
    rays = &detail::all_views_in_bands<Metric>;
  }
  return {method,
          name,
          MethodKind::kMetric,
          TargetRay::kNone,
          GainQuantity::kMetric,
          GainQuantity::kMetric,
          row.needs_distances,
          rays,
          cells,
          detail::free_dims<Metric>(),
          detail::quiet_cells<Metric>() == detail::QuietCells::kFar,
          detail::rear_side_rays<Metric>(),
          row.race_rounds,
          detail::cell_sum<Metric>() && detail::far_alike<Metric>(),
          detail::surface_cells<Metric>()};
}

// NOTE: the rounds of the metrics' races (MethodTraits::race_rounds): the worst rank of the exact
// best view among the estimates of all views, over the 48 oracle states of
// tests/gain/metrics_race_scenes_test.cpp: occlusion aware 5 by every 27th ray; unobserved voxel
// 40 by every 9th and 17 by every 3rd; average entropy 28 and 12; area factor 34 and 5. Each round
// keeps about twice that (BENCHMARK.md, "The metrics raced"; docs/model.md, "The metrics at
// speed"). The rear side metrics' value sits on few rays: their coarser rays rank too poorly to
// race. The surface model, like the proximity count, sits on the few rays that pass near a
// surface: raced with rounds of (9, 96) and (3, 32) it chose views of 0.86-0.998 of the best's
// value in 5 of the 48 states (tabletop-1 after 7 and 8 scans, tabletop-2 and pile-b after 8,
// pile-a after 6). Both are raced cell by cell instead (MetricEvaluator::cells).
constexpr MetricRound kOcclusionAwareRounds[] = {{27, 12}};
constexpr MetricRound kUnobservedVoxelRounds[] = {{9, 64}, {3, 24}};
constexpr MetricRound kAverageEntropyRounds[] = {{9, 48}, {3, 20}};
constexpr MetricRound kAreaFactorRounds[] = {{9, 56}, {3, 10}};

using Q = GainQuantity;

// NOTE: the rows' order is the order names are listed in messages.
constexpr std::array kMethods = {
    //           method                        name             ray    by bits, by cells
    target_model(GainMethod::kProbabilistic, "probabilistic", TargetRay::kPaper, Q::kPaperBits,
                 Q::kPaperCells),
    target_model(GainMethod::kSurvival, "survival", TargetRay::kSurvival, Q::kSurvivalBits,
                 Q::kSurvivalCells),
    target_model(GainMethod::kGreedy, "greedy", TargetRay::kUnblocked, Q::kCount, Q::kCount),
    metric<OcclusionAware>(GainMethod::kOcclusionAware, "occlusion-aware",
                           {.race_rounds = kOcclusionAwareRounds}),
    metric<UnobservedVoxel>(GainMethod::kUnobservedVoxel, "unobserved-voxel",
                            {.race_rounds = kUnobservedVoxelRounds}),
    metric<RearSideVoxel>(GainMethod::kRearSideVoxel, "rear-side-voxel"),
    metric<RearSideEntropy>(GainMethod::kRearSideEntropy, "rear-side-entropy"),
    metric<ProximityCount>(GainMethod::kProximityCount, "proximity-count",
                           {.needs_distances = true}),
    metric<AverageEntropy>(GainMethod::kAverageEntropy, "average-entropy",
                           {.race_rounds = kAverageEntropyRounds}),
    metric<AreaFactor>(GainMethod::kAreaFactor, "area-factor",
                       {.needs_distances = true, .race_rounds = kAreaFactorRounds}),
    metric<Surface>(GainMethod::kSurface, "surface", {.needs_distances = true}),
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

std::string_view to_string(GainObjective objective) {
  return objective == GainObjective::kCells ? "cells" : "bits";
}

GainObjective parse_gain_objective(std::string_view name) {
  if (name == "bits") return GainObjective::kBits;
  if (name == "cells") return GainObjective::kCells;
  throw std::invalid_argument(cat("unknown objective '", name, "' (expected bits or cells)"));
}

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
