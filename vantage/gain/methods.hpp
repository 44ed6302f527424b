#pragma once
/// @file
/// The gain methods' one registry: each GainMethod's name and what the rest of the library asks
/// of it, so that no other file switches on the method. Adding a method takes its own file (a
/// target predictor in models/target_predictors.hpp's shape, or a metric under
/// gain/models/metrics/) and one row in methods.cpp.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "vantage/gain/types.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

namespace detail {
struct MetricContext;
}  // namespace detail

/// How a method values a view.
enum class MethodKind {
  /// A prediction per unobserved target cell in the frustum, each on its own ray from the sensor
  /// (docs/model.md "One view"): exact.hpp.
  kTargetModel,
  /// A sum over the cells the view's pinhole rays cross (evaluators/metric_evaluator.hpp).
  kMetric,
};

/// The ray a target model walks to each target (models/target_predictors.hpp).
enum class TargetRay {
  kPaper,      ///< the paper's visibility HMM and occupancy filter (model.hpp)
  kSurvival,   ///< the survival reading of it (survival.hpp)
  kUnblocked,  ///< 1 if nothing occupied lies before the target, else 0 (simple greedy)
  kNone,       ///< a metric
};

/// A metric's evaluation of every view (models/metric_rays.hpp).
using MetricFn = std::vector<ViewGain> (*)(const detail::MetricContext&, std::span<const Frustum>,
                                           int num_threads);

/// A metric's credits cell by cell on a list of cells, with the rays each view saw stopped so far
/// (models/metric_cells.hpp, all_view_cells).
using MetricCellsFn = std::vector<ViewCells> (*)(const detail::MetricContext&,
                                                 std::span<const Frustum>,
                                                 std::span<const std::uint32_t> cells,
                                                 int num_threads,
                                                 std::span<StoppedRays* const> stopped);

/// A round of a metric's race (the swept search, docs/decision.md "The swept search"): the views
/// still in the race estimated by every `coarseness`-th of the metric's rays along each image axis
/// (MetricEvaluator::gains), the best `keep` of them passed on to the next round.
struct MetricRound {
  int coarseness;
  std::size_t keep;
};

/// What the library asks of a gain method.
struct MethodTraits {
  GainMethod method;
  std::string_view name;  ///< as the CLI, the files and the plots spell it
  MethodKind kind;
  TargetRay ray;  ///< kNone for a metric
  /// What it computes ranked by bits and by cells (GainObjective): two quantities for a model
  /// with the observability parameter a, the same one for greedy's count and a metric.
  GainQuantity by_bits, by_cells;
  /// A metric that reads each cell's distance to the nearest occupied cell.
  bool needs_distances;
  MetricFn metric;  ///< a metric's evaluation; nullptr for a target model
  /// A metric's credits cell by cell, when its value is a sum of them (detail::cell_sum), so that
  /// the swept search races it on samples of cells; nullptr for the others.
  MetricCellsFn cells = nullptr;
  /// A metric whose rays cross cubes of free cells of one value (MetricContext::uniform).
  bool crosses_uniform = false;
  /// A metric whose rays cross cubes of free cells and unobserved ones far from every occupied
  /// cell (MetricContext::far).
  bool crosses_far = false;
  /// A metric changed only by rays that end on a rear side (MetricContext::open, occupied).
  bool rear_side_rays = false;
  /// The rounds of a metric's race before the last, which evaluates the views left exactly;
  /// empty when its coarser rays rank too poorly to race, so that every view is evaluated
  /// exactly, or raced cell by cell (`cells`).
  std::span<const MetricRound> race_rounds = {};
  /// A metric raced cell by cell whose walk by codes crosses cubes of unobserved cells far from
  /// every occupied cell (MetricContext::far_unobserved).
  bool crosses_far_unobserved = false;
  /// A metric whose value is the surface a scan is expected to add [cells], by chances per cell
  /// (GainConfig::surface_rates) that a run fits from its own scans (SurfaceRateFit).
  bool surface_cells = false;

  /// What it computes when it ranks by `objective`: the one answer to "which quantity".
  constexpr GainQuantity quantity(GainObjective objective) const {
    return objective == GainObjective::kCells ? by_cells : by_bits;
  }
  /// Whether it ranks by bits or by expected cells as GainObjective says (and has the
  /// observability parameter a); the others have one value, their gain.
  constexpr bool has_objective() const { return by_bits != by_cells; }
};

/// The traits of `method`.
const MethodTraits& method_traits(GainMethod method);
/// Every method, in the enum's order.
std::span<const MethodTraits> gain_methods();
/// The method named `name`, if one is.
std::optional<GainMethod> find_gain_method(std::string_view name);

/// Whether `method` is one of the field's metrics (MethodKind::kMetric).
bool is_volumetric_metric(GainMethod method);

/// Throws std::invalid_argument, naming `who`, when `config.method` is one of the metrics: the
/// paper's evaluations (exact, fast) compute the paper's model or greedy's count only, and would
/// otherwise silently give the paper's model for a metric.
void require_model_method(const GainConfig& config, std::string_view who);

}  // namespace vantage
