#pragma once
/// @file
/// The paper's model of one ray (§3.1, §3.2; docs/model.md "One ray"): a visibility HMM along the
/// ray and a visibility-aware occupancy filter, which together predict the information a sensor
/// gains on the ray's target cell.

#include <cstddef>
#include <span>
#include <vector>

namespace vantage {

/// The paper's observability parameter a for a cluttered table top (§5.1, §6): the default.
inline constexpr double kTableTopAlpha = 0.997;
/// The paper's a for an office building (§5.2): little penalty for looking into unobserved space.
inline constexpr double kOfficeAlpha = 0.9999;

/// Binary entropy of p in bits; 0 at p = 0 and p = 1.
double entropy_bits(double p);

/// The model's state after folding in cells c_0 … c_m of a ray.
struct RayState {
  int m = 0;                ///< index of the last cell folded in
  double t = 1.0;           ///< a^m, the chance to stay visible (eq. 10)
  double visibility = 1.0;  ///< v_m = p(x_m), eqs. (5)–(7)
  double posterior = 0.5;   ///< q_m = p(o_m | x_m, z_{1:m}), eqs. (11)–(15)
  double occupancy = 0.5;   ///< p_m, the map's occupancy probability of c_m

  /// Expected information gain on c_m if c_m is the target, eq. (4): H(p_m) - H(q_m) [bits].
  double gain() const { return entropy_bits(occupancy) - entropy_bits(posterior); }
};

/// The visibility-aware ray model with observability parameter `a` (alpha), in the direct form of
/// docs/model.md: the readable reference that `vantage ray` prints. The evaluations run the same
/// model in odds form, `PaperModel` (model.hpp); tests pin the two together to 1e-12.
class RayModel {
 public:
  /// Throws std::invalid_argument unless 0 < alpha <= 1.
  explicit RayModel(double alpha);

  double alpha() const { return alpha_; }

  /// State at the origin's cell c_0: v_0 = 1, q_0 = p_0.
  static RayState start(double p0);

  /// Folds in the next cell c_m with occupancy p_m (docs/model.md, for m >= 1).
  RayState step(const RayState& prev, double p_m) const;

  /// Runs the model over a whole ray of occupancy probabilities; one state per cell.
  /// Throws std::invalid_argument when the ray is empty or a probability lies outside [0, 1].
  std::vector<RayState> trace(std::span<const double> occupancy) const;

 private:
  double alpha_;
};

/// The model's states after a prefix of k cells that all have occupancy p, for k = 1 … n.
///
/// Cells outside the grid between the sensor and the grid count as free with p = p_min
/// (docs/model.md), so the state where a ray enters the grid depends only on how many cells it
/// skipped: `at(k)` is the state after c_0 … c_{k-1}, ready to step into c_k.
///
/// The table is built once and read-only afterwards, so threads may share it.
class UniformPrefix {
 public:
  /// Precomputes the states for k = 1 … max_cells.
  UniformPrefix(const RayModel& model, double p, int max_cells);

  /// State after k cells of occupancy p, 1 <= k <= size().
  const RayState& at(int k) const { return states_[static_cast<std::size_t>(k - 1)]; }
  int size() const { return static_cast<int>(states_.size()); }

 private:
  std::vector<RayState> states_;  // states_[k - 1] is the state after k cells
};

/// Whether a ray of occupancies reaches its last cell under the simple greedy model (infinite
/// visibility): no cell before the last occludes (`occludes`, map/line_of_sight.hpp).
bool greedy_visible(std::span<const double> occupancy);

}  // namespace vantage
