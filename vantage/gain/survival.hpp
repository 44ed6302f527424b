#pragma once
/// @file
/// The survival reading of the visibility (docs/model.md, "The survival reading"): a named
/// variant of eqs. (9)-(10), measured against the literal model, never in its place.
///
/// An unobserved cell a ray passes may hold a surface not yet seen; the ray survives it with
/// probability a. A free cell never stops it and an occupied one always does, and a ray once
/// stopped stays stopped (eq. 9 with no way back from hidden to visible). So the target's
/// visibility is v_M = a^(unobserved cells before it) when no occupied cell lies before it, and
/// 0 otherwise: simple greedy (v_M = 1 unless blocked) is the case a = 1, and a is the chance that
/// one unobserved cell is empty air, a property of the scene's clutter rather than of the
/// sensor's distance. The occupancy posterior is the paper's filter (eqs. 11-15) on this v.

#include <vector>

#include "vantage/gain/model.hpp"
#include "vantage/gain/snapshot.hpp"

namespace vantage {

/// One ray under the survival reading, in the direct form. Built once per evaluation and only
/// read after, so threads may share it.
class SurvivalModel {
 public:
  /// The state after folding in cells c_0 ... c_m.
  struct State {
    double visibility = 1.0;  ///< v_m
    double posterior = 0.5;   ///< q_m
  };

  /// `alpha` in (0, 1]; cells outside the grid count as free at `p_min`, up to `max_cells` of
  /// them (docs/model.md, "One ray").
  SurvivalModel(double alpha, double p_min, int max_cells);

  /// The state in the first grid cell a ray visits, c_m: the origin's cell when m = 0, else
  /// after m free cells outside the grid.
  State enter(int m, const GainMap::Value& cell) const;
  /// Folds in `cell` after `prev`.
  void step(State& s, const GainMap::Value& prev, const GainMap::Value& cell) const;
  /// What the target predicts once its cell is folded in: eq. (4) and v_M.
  static TargetPrediction predict(const State& s, const GainMap::Value& target);

 private:
  double alpha_;
  std::vector<double> outside_;  ///< outside_[k]: q after k + 1 free cells at p_min
};

}  // namespace vantage
