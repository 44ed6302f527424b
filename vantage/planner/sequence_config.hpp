#pragma once
/// @file
/// The settings of a decision that plans past the next scan (sequence.hpp), at the bottom of the
/// planner's layer so that PlannerConfig (types.hpp) holds them.

#include <Eigen/Core>

#include "vantage/views/travel.hpp"

namespace vantage {

/// Settings of the sequence decision. horizon 1 with travel_weight 0 is the one-view decision.
struct SequenceConfig {
  /// K: views in the planned sequence, in [1, kMaxHorizon]; the tour is ordered by brute force
  /// over its K! orders.
  int horizon = 1;
  /// What a metre of tour costs, as a share of the best single view's value at this decision
  /// [1/m]: the sequence maximises J(S) - travel_weight * max_c J({c}) * tour(S). Relative, so
  /// one weight means the same early in a run (thousands of cells in view) and late (tens).
  double travel_weight = 0.0;
  /// M: only the M candidates of highest single-view value take part (ties: the lower index);
  /// their per-cell visibilities are what the sequence holds in memory [views], >= 1.
  int shortlist = 40;
  /// Travel between two candidates' sensor positions. The travel from the current pose to a
  /// candidate is the candidate's own.
  TravelRule travel;
  /// 0: every view's values exact. k > 0: every view's per-cell visibilities on a hashed sample
  /// of one unobserved cell in 2^k (in_cell_sample, exact.hpp), values scaled by 2^k (estimates;
  /// the shortlist then costs nothing), in [0, 16].
  int sample_bits = 0;

  static constexpr int kMaxHorizon = 6;

  /// Whether the decision plans a sequence (horizon > 1 or a travel weight).
  bool active() const { return horizon > 1 || travel_weight > 0.0; }
  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// What PlannerMethod::kSequence plans when its SequenceConfig plans one view: K = 3 views, a
/// metre of tour at 0.1 of the best view's value (the ring's best setting, RESULTS.md).
struct SequenceDefaults {
  int horizon;
  double travel_weight;  ///< [1/m]
};
inline constexpr SequenceDefaults kSequenceDefaults{3, 0.1};

}  // namespace vantage
