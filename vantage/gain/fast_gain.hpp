#pragma once
/// @file
/// Fast gain evaluation (docs/fast-gain.md): rays cast outward through each candidate's frustum,
/// every ray carrying the model's state (MODEL.md "One ray") along itself, and every unobserved
/// cell credited once per view, by the ray that owns it.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "vantage/gain/ray_model.hpp"
#include "vantage/gain/view_gain.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// A read-only snapshot of an occupancy grid, laid out for gain evaluation: per cell a small code
/// into a table of the distinct log-odds values the grid holds, each with its probability,
/// entropy and class. A grid updated by hits and misses holds few distinct values, so the codes
/// are usually one byte (a 129 x 129 x 65 grid fits in 1 MiB of cache).
///
/// Probabilities and classes are computed from the stored log-odds exactly as OccupancyGrid does,
/// so a model run on the snapshot gives the same numbers as one run on the grid.
class GainMap {
 public:
  /// What the evaluation needs to know about a cell.
  struct Value {
    double p = 0.5;        ///< occupancy probability
    double entropy = 1.0;  ///< H(p) [bits]
    CellState state = CellState::kUnobserved;
  };

  /// Takes the snapshot; `num_threads` as everywhere (0 = all cores).
  explicit GainMap(const OccupancyGrid& grid, int num_threads = 0);

  const GridSpec& spec() const { return spec_; }
  const OccupancyParams& params() const { return params_; }
  std::size_t size() const { return spec_.num_cells(); }

  /// Bytes per cell code: 1, 2 or 4.
  int code_width() const { return code_width_; }
  /// The table of distinct values, ascending in log-odds.
  std::span<const Value> values() const { return values_; }
  /// Codes of width `Code` (which must match code_width()), one per cell in linear order.
  template <typename Code>
  const Code* codes() const {
    if constexpr (sizeof(Code) == 1) {
      return codes8_.data();
    } else if constexpr (sizeof(Code) == 2) {
      return codes16_.data();
    } else {
      return codes32_.data();
    }
  }
  /// The value of cell `i`, whatever the code width.
  const Value& value(std::size_t i) const;

 private:
  GridSpec spec_;
  OccupancyParams params_;
  int code_width_ = 1;
  std::vector<Value> values_;
  // The codes, in the one vector of width code_width_.
  std::vector<std::uint8_t> codes8_;
  std::vector<std::uint16_t> codes16_;
  std::vector<std::uint32_t> codes32_;
};

namespace detail {

/// The same model in odds form, without divisions: visibility v = n / (n + d) and posterior
/// q = a / (a + b), each pair scaled freely. One step is a few multiply-adds, so a long ray costs
/// no division per cell; renormalize() keeps the pairs in range.
struct Odds {
  double n = 1.0, d = 0.0;  ///< visibility odds
  double a = 0.5, b = 0.5;  ///< occupancy odds

  Odds() = default;
  Odds(double v, double q) : n(v), d(1.0 - v), a(q), b(1.0 - q) {}
  explicit Odds(const RayState& s) : Odds(s.visibility, s.posterior) {}

  double visibility() const { return n / (n + d); }
  double posterior() const { return a / (a + b); }

  /// Folds in cell c_m: `t` = a^m, `p_prev` the occupancy of c_{m-1}, `p` that of c_m.
  void step(double t, double p_prev, double p) {
    const double n1 = (t * n + 0.1 * d) * (1.0 - p_prev);  // eqs. (5)-(7), (9)
    const double d1 = ((1.0 - t) * n + 0.9 * d) * p_prev;
    // tau = (2n + d) / 2(n + d) and 1 - tau = d / 2(n + d), eq. (15); the common factor cancels.
    const double keep = 2.0 * n1 + d1;
    const double a1 = (keep * a + d1 * b) * p;  // eqs. (12), (14)
    const double b1 = (d1 * a + keep * b) * (1.0 - p);
    n = n1;
    d = d1;
    a = a1;
    b = b1;
  }
  /// Scales both pairs back to sum 1; call every few steps.
  void renormalize() {
    const double sv = 1.0 / (n + d), sq = 1.0 / (a + b);
    n *= sv;
    d *= sv;
    a *= sq;
    b *= sq;
  }
  /// v < epsilon.
  bool hidden(double epsilon) const { return n < epsilon * (n + d); }
  /// |q - 0.5| < epsilon.
  bool pinned(double epsilon) const { return std::abs(a - b) < 2.0 * epsilon * (a + b); }
};

/// Inclusive index box of the grid cells that may lie inside a frustum (its bounding box, cut to
/// the grid); empty when the frustum misses the grid.
struct CellBox {
  Index3 lo, hi;
  bool empty() const { return (hi.array() < lo.array()).any(); }
};

inline CellBox cells_under(const GridSpec& spec, const Frustum& view) {
  const Eigen::AlignedBox3d box = view.bounds();
  return {spec.lattice_index(box.min()).cwiseMax(Index3::Zero()),
          spec.lattice_index(box.max()).cwiseMin(spec.dims - Index3::Ones())};
}

}  // namespace detail

/// Fast evaluation of every view (GainEvaluation::kFast), whatever `config.evaluation` says. The
/// grid is only read.
///
/// The probabilistic method casts rays; the greedy one has no state to carry along a ray, and an
/// exact line of sight stops at the first occupied cell, so its fast mode is the exact one.
std::vector<ViewGain> fast_view_gains(const OccupancyGrid& grid, std::span<const Frustum> views,
                                      const GainConfig& config);

/// The same on a snapshot taken earlier, for callers that evaluate one map state repeatedly.
std::vector<ViewGain> fast_view_gains(const GainMap& map, std::span<const Frustum> views,
                                      const GainConfig& config);

/// The cheaper of the fast and the exact evaluation on this map state (GainEvaluation::kAuto,
/// docs/fast-gain.md "Choosing per map state"), bit for bit the one chosen. The choice comes from
/// counts taken before any ray is cast, so it does not depend on time or threads.
std::vector<ViewGain> cheapest_view_gains(const OccupancyGrid& grid, std::span<const Frustum> views,
                                          const GainConfig& config);

/// The exact evaluation (exact_view_gains) on a snapshot taken earlier.
std::vector<ViewGain> exact_view_gains(const GainMap& map, std::span<const Frustum> views,
                                       const GainConfig& config);

}  // namespace vantage
