#pragma once
/// @file
/// The gain layer's shared types, at its bottom (docs/architecture.md): which model predicts a
/// cell's gain (GainMethod, whose traits live in the registry, methods.hpp), what a decision
/// ranks by (GainObjective) and so which quantity it computes (GainQuantity), how a view's gain is
/// evaluated (GainEvaluation), the settings (GainConfig) and the result (ViewGain).

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "vantage/gain/ray_model.hpp"

namespace vantage {

/// How the gain of one target cell is predicted.
enum class GainMethod {
  kProbabilistic,  ///< the paper's visibility HMM and occupancy filter, parameter alpha
  kGreedy,  ///< simple greedy: 1 if nothing occupied lies before the cell (infinite visibility)
  /// The survival reading of the visibility (survival.hpp, docs/model.md): a ray survives each
  /// unobserved cell with probability alpha, free cells always, occupied cells never; the
  /// paper's occupancy filter on top.
  kSurvival,
  // The field's volumetric metrics (vantage/gain/evaluators/metric_evaluator.hpp, docs/model.md
  // "The field's metrics"): sums over the cells the view's rays cross, not per-target predictions.
  kOcclusionAware,   ///< entropy weighted by visibility, eq. M1
  kUnobservedVoxel,  ///< unobserved cells reached, eq. M2
  kRearSideVoxel,    ///< occupied cells reached from unobserved ones, eq. M3
  kRearSideEntropy,  ///< visible entropy on rays that end on a rear side, eq. M4
  kProximityCount,   ///< unobserved cells near occupied ones, eq. M5
  kAverageEntropy,   ///< Kriegel's mean entropy of the cells reached, eq. M6
  kAreaFactor,       ///< Vasquez-Gomez's area factor, eq. M7
  /// The surface the view's rays reach first (issue 37, gain/models/metrics/surface.hpp): the
  /// survival reading on the metrics' rays, with the chance that an unobserved cell holds a surface
  /// taken by its distance to the nearest occupied cell (GainConfig::surface_rates, fitted online).
  kSurface,
};

std::string_view to_string(GainMethod method);
/// Parses "probabilistic", "survival", "greedy" or a metric's name (occlusion-aware,
/// unobserved-voxel, rear-side-voxel, rear-side-entropy, proximity-count, average-entropy,
/// area-factor) or "surface"; throws std::invalid_argument naming the value.
GainMethod parse_gain_method(std::string_view name);

/// What a model with the observability parameter a (the paper's, the survival reading) ranks by;
/// the others have one value, whatever it says.
enum class GainObjective {
  kBits,   ///< the expected information gain of eq. (1), ViewGain::gain [bits]
  kCells,  ///< the expected number of unobserved cells seen, ViewGain::cells [cells]
};

std::string_view to_string(GainObjective objective);
/// Parses "bits" or "cells"; throws std::invalid_argument naming the value.
GainObjective parse_gain_objective(std::string_view name);

/// Which quantity a decision computes for every view: the one type that says it. The registry
/// answers it from a method and its objective (MethodTraits::quantity, methods.hpp); the searches
/// rank by it, the bounds bound it (evaluators/bounds.hpp), and the hierarchical count
/// (evaluators/hierarchy.hpp) and the swept rays (evaluators/swept.hpp) compute those that read
/// the cells' classes alone (counts_classes).
enum class GainQuantity {
  kPaperBits,      ///< the paper's eq. (4) gain, at most H(p) a target: ViewGain::gain [bits]
  kPaperCells,     ///< the paper's expected cells seen, the sum of v_M: ViewGain::cells [cells]
  kSurvivalBits,   ///< the survival reading's eq. (4) gain: ViewGain::gain [bits]
  kSurvivalCells,  ///< the survival reading's expected cells seen: ViewGain::cells [cells]
  kCount,          ///< greedy's count of the targets nothing occupied hides: both fields [cells]
  kMetric,         ///< a metric's value: ViewGain::gain
};

/// Whether `quantity` is a sum over cells [cells] (ViewGain::cells), not ViewGain::gain.
constexpr bool in_cells(GainQuantity quantity) {
  return quantity == GainQuantity::kPaperCells || quantity == GainQuantity::kSurvivalCells ||
         quantity == GainQuantity::kCount;
}

/// Whether `quantity` reads the cells' classes alone, not their occupancy (the survival reading's
/// cells, greedy's count): what the hierarchical count and the swept rays compute.
constexpr bool counts_classes(GainQuantity quantity) {
  return quantity == GainQuantity::kSurvivalCells || quantity == GainQuantity::kCount;
}

/// How finely a view's gain is computed. The target models always take one ray from the sensor
/// to the centre of every unobserved cell in the frustum (the paper's definition, exact.hpp):
/// the fast evaluation that cast rays outward instead cost as much or more in every state
/// measured and was removed (BENCHMARK.md, "One planner").
enum class GainEvaluation {
  kExact,  ///< a metric's every pixel ray (evaluators/metric_evaluator.hpp)
  kAuto,   ///< a metric's every third ray along each image axis (evaluators/metric_evaluator.hpp)
};

std::string_view to_string(GainEvaluation evaluation);
/// Parses "exact" or "auto"; throws std::invalid_argument naming the value.
GainEvaluation parse_gain_evaluation(std::string_view name);

/// The surface model's distance classes (gain/models/metrics/surface.hpp): an unobserved cell whose
/// centre lies within 1, 2, 3 or 4 cells of the nearest occupied cell's, or farther.
inline constexpr std::size_t kSurfaceClasses = 5;

/// Per distance class, the chance that an unobserved cell holds a surface: the share of such
/// cells that a scan turned occupied among those it turned known (SurfaceRateFit).
using SurfaceRates = std::array<double, kSurfaceClasses>;

/// The rates before any scan is seen: 1 - the survival reading's a (kSurvivalAlpha, 0.995) in
/// every class, the chance that one unobserved cell hides a surface wherever it lies. The fit
/// replaces them from the first scan on.
inline constexpr SurfaceRates kSurfacePrior = {0.005, 0.005, 0.005, 0.005, 0.005};

/// Settings of a gain evaluation.
struct GainConfig {
  GainMethod method = GainMethod::kProbabilistic;
  GainEvaluation evaluation = GainEvaluation::kAuto;  ///< used by evaluate_views
  double alpha = kTableTopAlpha;                      ///< observability parameter a, in (0, 1]
  /// Early stop, in [0, 0.5): a ray stops once its visibility falls below epsilon. 0 gives the
  /// literal model of docs/model.md.
  double epsilon = 1e-6;
  /// The metrics: spacing of neighbouring rays at the farthest cell in view [cells], in (0, 1].
  /// At most 1/sqrt(2) (the default) guarantees that every cell in view is crossed by a ray.
  double ray_spacing = 0.7071;
  int num_threads = 0;  ///< 0 = all cores; results are identical for any count
  /// The surface model's chances per distance class, each in [0, 1] (kSurface only).
  SurfaceRates surface_rates = kSurfacePrior;

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// The predicted gain of one view.
struct ViewGain {
  double gain = 0.0;  ///< expected information gain of the view, eq. (1) [bits]
  /// Expected number of the unobserved cells in view that the view sees, E (docs/model.md "The
  /// expected number of cells seen"): the sum of v_M, the visibility of each target [cells]. For
  /// greedy, its count of unblocked targets (= gain).
  double cells = 0.0;
  /// The unobserved cells inside the frustum.
  std::size_t targets = 0;

  /// Its value of `quantity`: ViewGain::cells for a quantity in cells (greedy's count too, whose
  /// gain equals it), else ViewGain::gain.
  double value(GainQuantity quantity) const { return in_cells(quantity) ? cells : gain; }
  /// A gain that holds `value` as `quantity`, the other field 0 (both for greedy's count, whose
  /// gain is its count) and no targets: a search's estimate or bound.
  static ViewGain of(GainQuantity quantity, double value) {
    ViewGain out;
    (in_cells(quantity) ? out.cells : out.gain) = value;
    if (quantity == GainQuantity::kCount) out.gain = value;
    return out;
  }

  /// Adds `other`'s three sums: the gain of several views (a candidate's, a view's rows).
  ViewGain& operator+=(const ViewGain& other) {
    gain += other.gain;
    cells += other.cells;
    targets += other.targets;
    return *this;
  }
};

/// One view's unobserved targets with a value above 0, in ascending linear index: their v_M
/// (view_cells.hpp), or a metric's credits (models/metric_cells.hpp).
struct ViewCells {
  std::vector<std::uint32_t> cells;  ///< linear indices of the targets, ascending
  std::vector<double> seen;          ///< v_M of each, in (0, 1] [cells]; or its credit
  std::size_t targets = 0;           ///< unobserved cells inside the frustum, seen or not

  /// The sum of `seen` in ascending cell order [cells]; equal to ViewGain::cells of the exact
  /// evaluation up to the order of the additions.
  double sum() const;
};

/// The rays of one view's image that its cell-by-cell credits (models/metric_cells.hpp) walked
/// and saw stopped by an occupied cell: per ray (row * cols + col of the view's RayImage), the
/// segment's parameter where it enters that cell. A cell the ray enters only past it is not
/// reached by that ray. What a race keeps across its rounds, so that a ray to the cells of one
/// surface is walked to its stop once, not once a cell (docs/decision.md, "A metric raced cell
/// by cell").
struct StoppedRays {
  std::unordered_map<std::uint32_t, double> at;
};

}  // namespace vantage
