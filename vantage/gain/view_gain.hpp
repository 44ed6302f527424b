#pragma once
/// @file
/// Expected information gain of candidate views (eqs. 1, 3, 4; MODEL.md "One view").

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vantage/gain/ray_model.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// How the gain of one target cell is predicted.
enum class GainMethod {
  kProbabilistic,  ///< the paper's visibility HMM and occupancy filter, parameter alpha
  kGreedy,  ///< simple greedy: 1 if nothing occupied lies before the cell (infinite visibility)
};

std::string_view to_string(GainMethod method);
/// Parses "probabilistic" or "greedy"; throws std::invalid_argument naming the value.
GainMethod parse_gain_method(std::string_view name);

/// How a view's gain is computed from the per-cell model.
enum class GainEvaluation {
  /// One ray from the sensor to the centre of every unobserved cell in the frustum: the paper's
  /// definition and the reference.
  kExact,
  /// Rays cast outward through the frustum, each carrying the model's state along itself and
  /// crediting the cells it owns (vantage/gain/fast_gain.hpp, docs/fast-gain.md).
  kFast,
  /// Whichever of the two costs less on this map state and these views, by counts taken before
  /// any ray is cast (docs/fast-gain.md, "Choosing per map state"). Deterministic.
  kAuto,
};

std::string_view to_string(GainEvaluation evaluation);
/// Parses "exact", "fast" or "auto"; throws std::invalid_argument naming the value.
GainEvaluation parse_gain_evaluation(std::string_view name);

/// Settings of a gain evaluation.
struct GainConfig {
  GainMethod method = GainMethod::kProbabilistic;
  GainEvaluation evaluation = GainEvaluation::kAuto;  ///< used by evaluate_views
  double alpha = kTableTopAlpha;                      ///< observability parameter a, in (0, 1]
  /// Early stop, in [0, 0.5): a ray stops once its visibility falls below epsilon. In the fast
  /// mode an unobserved cell whose posterior lies within epsilon of 0.5 ("pinned", gain below
  /// 3 epsilon^2 bits) is not credited, and a pinned ray crosses uniform unobserved space in one
  /// jump. 0 gives the literal model of MODEL.md.
  double epsilon = 1e-6;
  /// Fast mode: spacing of neighbouring rays at the farthest cell in view [cells], in (0, 1].
  /// At most 1/sqrt(2) (the default) guarantees that every cell in view is crossed by the ray
  /// that owns it.
  double ray_spacing = 0.7071;
  int num_threads = 0;  ///< 0 = all cores; results are identical for any count

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// The predicted gain of one view.
struct ViewGain {
  double gain = 0.0;  ///< expected number of unobserved cells the view turns known [bits]
  /// Exact mode: the unobserved cells inside the frustum. Fast mode: those it credited; the same
  /// cells with epsilon = 0, without those behind a ray's early stop and those deep in uniform
  /// unobserved space with a pinned posterior otherwise.
  std::size_t targets = 0;
};

/// Gains of all views, by the evaluation `config.evaluation` names. The grid is only read.
std::vector<ViewGain> evaluate_views(const OccupancyGrid& grid, std::span<const Frustum> views,
                                     const GainConfig& config);

/// Exact evaluation: every unobserved cell inside the frustum on its own ray from the sensor
/// origin to the cell's centre, summed. The reference for every faster evaluation; with
/// `config.epsilon` = 0 it is the literal model. Ignores `config.evaluation`.
std::vector<ViewGain> exact_view_gains(const OccupancyGrid& grid, std::span<const Frustum> views,
                                       const GainConfig& config);

/// Exact gain of one view.
ViewGain exact_view_gain(const OccupancyGrid& grid, const Frustum& view, const GainConfig& config);

/// Predicted gain of one target cell seen from `origin`, whatever its state (known cells are
/// evaluated too; the view sums skip them). Follows the literal model whatever `config.epsilon`
/// says.
double exact_cell_gain(const OccupancyGrid& grid, const Eigen::Vector3d& origin,
                       const Index3& target, const GainConfig& config);

}  // namespace vantage
