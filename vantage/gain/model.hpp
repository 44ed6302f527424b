#pragma once
/// @file
/// The ray model every gain evaluation runs (docs/model.md "One ray", eqs. 5-15): the state it
/// carries along a ray, the one step that folds in a cell (`PaperModel::step`), and the tables
/// one evaluation builds once (a^m, the free cells before the grid).
///
/// Where to change the model: `PaperModel` below (docs/model.md, top). The exact evaluation and
/// the OctoMap baseline of the benchmarks are templates on the model type; `BlindModel` is the
/// probe the tests use to show that the evaluation follows it.

#include <cmath>
#include <cstddef>
#include <vector>

namespace vantage {

/// The model's state after folding in cells c_0 … c_m, in odds form and without divisions:
/// visibility v = n / (n + d), posterior q = a / (a + b), each pair scaled freely. renormalize()
/// keeps the pairs in range.
struct RayOdds {
  double n = 1.0, d = 0.0;  ///< visibility odds
  double a = 0.5, b = 0.5;  ///< occupancy odds

  RayOdds() = default;
  RayOdds(double v, double q) : n(v), d(1.0 - v), a(q), b(1.0 - q) {}

  double visibility() const { return n / (n + d); }
  double posterior() const { return a / (a + b); }

  /// Scales both pairs back to sum 1.
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

/// What the model predicts for one target cell c_M.
struct TargetPrediction {
  double gain = 0.0;  ///< eq. (4): H(p_M) - H(q_M) [bits]
  double seen = 0.0;  ///< v_M, the chance the target is seen [cells]
};

/// The paper's model of one ray: the visibility HMM and the visibility-aware occupancy filter.
/// THE place to change the ray model: every evaluation steps with `step`. `RayModel`
/// (ray_model.hpp) is its readable twin, pinned to it by tests.
struct PaperModel {
  /// The state at the origin's cell c_0: v_0 = 1, q_0 = p_0.
  static RayOdds start(double p0) { return {1.0, p0}; }

  /// Folds in cell c_m: `t` = a^m, `p_prev` the occupancy of c_{m-1}, `p` that of c_m. A few
  /// multiply-adds, so a long ray costs no division per cell.
  static void step(RayOdds& s, double t, double p_prev, double p) {
    const double n1 = (t * s.n + 0.1 * s.d) * (1.0 - p_prev);  // eqs. (5)-(7), (9)
    const double d1 = ((1.0 - t) * s.n + 0.9 * s.d) * p_prev;
    // tau = (2n + d) / 2(n + d) and 1 - tau = d / 2(n + d), eq. (15); the common factor cancels.
    const double keep = 2.0 * n1 + d1;
    const double a1 = (keep * s.a + d1 * s.b) * p;  // eqs. (12), (14)
    const double b1 = (d1 * s.a + keep * s.b) * (1.0 - p);
    s.n = n1;
    s.d = d1;
    s.a = a1;
    s.b = b1;
  }

  /// The states after k = 1 … n cells that all have occupancy p (`run[k - 1]`), for the free
  /// cells before the grid.
  /// NOTE: computed by RayModel::step, the direct form, as before the gain code was split: the
  /// two forms agree to 1e-12 (tests/gain/model_test.cpp), not to the last bit, and the outputs
  /// of every run stay bit for bit those of before.
  static std::vector<RayOdds> uniform_run(double alpha, double p, int n);
};

/// A model that sees nothing: every cell after the origin's is hidden, so the posterior keeps the
/// map's occupancy and no cell gains anything. A probe for the tests: evaluated with it, the
/// exact evaluation must predict nothing.
struct BlindModel {
  static RayOdds start(double p0) { return {1.0, p0}; }
  static void step(RayOdds& s, double /*t*/, double /*p_prev*/, double p) { s = RayOdds(0.0, p); }
  /// As PaperModel::uniform_run, by `step`.
  static std::vector<RayOdds> uniform_run(double alpha, double p, int n);
};

/// What every ray of one evaluation shares, built once: a^m, and the states after the free cells
/// between the sensor and the grid (docs/model.md: outside the grid is free with p = p_min), so the
/// state where a ray enters the grid is a lookup indexed by the cells it skipped.
template <typename Model>
struct RayTables {
  /// Tables for m = 0 … max_cells.
  RayTables(double alpha, double p_min_, int max_cells) : p_min(p_min_) {
    const auto size = static_cast<std::size_t>(max_cells) + 1;
    t.resize(size);
    t[0] = 1.0;
    for (std::size_t m = 1; m < size; ++m) t[m] = t[m - 1] * alpha;
    outside = Model::uniform_run(alpha, p_min, max_cells);
    outside.insert(outside.begin(), RayOdds());  // outside[k] after k cells; 0 is unused
  }

  std::vector<double> t;         ///< t[m] = a^m, eq. (10)
  std::vector<RayOdds> outside;  ///< outside[k]: the state after k free cells, k >= 1
  double p_min;                  ///< occupancy of the cells outside the grid

  /// The state in the first grid cell a ray visits, c_m with occupancy p: the origin's cell when
  /// m = 0, else the free cells before it and a step into c_m.
  RayOdds enter(int m, double p) const {
    if (m == 0) return Model::start(p);
    RayOdds s = outside[static_cast<std::size_t>(m)];
    Model::step(s, t[static_cast<std::size_t>(m)], p_min, p);
    return s;
  }

  /// Folds in c_m (after c_{m-1} of occupancy p_prev) and keeps the pairs in range every 8 cells.
  void step(RayOdds& s, int m, double p_prev, double p) const {
    Model::step(s, t[static_cast<std::size_t>(m)], p_prev, p);
    if ((m & 7) == 0) s.renormalize();
  }
};

}  // namespace vantage
