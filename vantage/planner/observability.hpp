#pragma once
/// @file
/// The observability parameter a chosen automatically from the run's own outcomes: the paper's
/// §6 future work ("recognizes ... what observability strategy is the best").
///
/// No fixed a predicts well through a whole run: early, with the scene mostly unknown, a view
/// sees deep into unobserved space (a near 1); once the visible surfaces are known, what is left
/// hides behind objects not yet seen (a lower). So before each scan the chosen view's expected
/// number of cells seen, E(a) (docs/model.md), is predicted under every candidate a; after the
/// scan the cells it really turned known are counted; the next decision uses the a whose
/// predictions have matched best, recent scans weighing more.

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vantage/gain/ray_model.hpp"
#include "vantage/gain/types.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/planner/types.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

/// The observability a of the probabilistic method: a fixed value, or fitted from the run's own
/// outcomes (ObservabilityFit), starting from `value`.
struct AlphaSetting {
  bool automatic = false;
  double value = kTableTopAlpha;  ///< the fixed a, or the prior of the fit, in (0, 1]

  /// "0.997" (the value to 15 significant digits) or "auto".
  std::string label() const;
  friend bool operator==(const AlphaSetting&, const AlphaSetting&) = default;
};

/// Parses "auto" (with `prior` as its starting value) or a number in (0, 1]; throws
/// std::invalid_argument naming the text.
AlphaSetting parse_alpha_setting(std::string_view text, double prior = kTableTopAlpha);

/// The expected number of cells seen (ViewGain::cells) of `views` together, under each of
/// `alphas` in turn, with the rest of `config` (its method is kept when it is survival, else taken
/// as probabilistic) [cells]:
/// the predictions ObservabilityFit::record takes for the views a scan is about to be taken from.
std::vector<double> expected_cells_by_alpha(const OccupancyGrid& grid,
                                            std::span<const Frustum> views, GainConfig config,
                                            std::span<const double> alphas);

/// Settings of the online fit.
struct ObservabilityFitConfig {
  /// The values of a each scan's view is evaluated under, ascending, each in (0, 1); the fit
  /// interpolates between them (ln E against ln(1 - a), piecewise linear) and may choose any a
  /// in their range. The default spans the paper's
  /// table-top (0.997) and office (0.9999) values and a decade either side in 1 - a; each costs
  /// one evaluation of the scanned view per scan.
  std::vector<double> alphas = {0.99, 0.995, 0.997, 0.999, 0.9995, 0.9999, 0.99999};
  double prior = kTableTopAlpha;  ///< the a in force until the first outcome, in (0, 1]
  /// Weight of an outcome relative to the one after it, in (0, 1]: 1 weighs all scans alike,
  /// 0.5 halves the weight of each older scan.
  double recency = 0.5;

  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// The survival reading's a (gain/survival.hpp): the chance that one unobserved cell is empty
/// air. The default where nothing is fitted (vantage plan) and the prior of the fit; chosen, like
/// the paper's 0.997, by measurement: the best fixed a on the 8 calibration runs of RESULTS.md
/// ("The survival reading"). An exploration's fit never uses the prior: its first scan calibrates.
inline constexpr double kSurvivalAlpha = 0.995;

/// The fit for the survival reading: its a is a chance per unobserved cell, not per cell from
/// the sensor, so its values span clutter (0.9: one cell in ten hides a surface) to greedy's
/// clear air (0.9995), starting from kSurvivalAlpha.
ObservabilityFitConfig survival_fit_config();

/// The a a method uses when none is given: the survival reading's kSurvivalAlpha, else the
/// paper's for the scene (`literal`: 0.997 on a table top, 0.9999 in an office).
double default_alpha(PlannerMethod method, double literal);

/// Fits a to the predictions and outcomes of the scans taken so far. Deterministic: the same
/// outcomes give the same a.
class ObservabilityFit {
 public:
  /// Validates the config; throws std::invalid_argument naming the field.
  explicit ObservabilityFit(ObservabilityFitConfig config = {});

  /// The candidate values of a, in the order record() expects its predictions.
  const std::vector<double>& alphas() const { return config_.alphas; }

  /// Records one scan: `expected_cells[j]`, the cells the scan's view was predicted to see under
  /// alphas()[j] before it was taken [cells], and `actual_cells`, the cells it turned known.
  /// Throws std::invalid_argument for a size mismatch or a negative or non-finite count.
  void record(std::span<const double> expected_cells, double actual_cells);

  /// The a for the next decision: the prior before any outcome, then the a in the range of
  /// alphas() with the least recency-weighted error |ln((E(a) + 1) / (actual + 1))| (a ratio, so
  /// that a scan that sees 100 000 cells and one that sees 1 000 count alike), E(a) interpolated
  /// between the evaluated values; searched on kSearchSteps points per interval of alphas().
  /// Ties go to the lower a.
  double alpha() const;

  /// The recency-weighted error of the outcomes so far, were `alpha` in force (the sum alpha()
  /// minimises). `alpha` must lie in the range of alphas().
  double error(double alpha) const;
  std::size_t outcomes() const { return outcomes_.size(); }

  static constexpr int kSearchSteps = 32;

 private:
  struct Outcome {
    std::vector<double> log_expected;  // ln(E + 1) per candidate a
    double log_actual = 0.0;           // ln(actual + 1)
  };
  ObservabilityFitConfig config_;
  std::vector<double> x_;  // ln(1 - a) per candidate a, descending
  std::vector<Outcome> outcomes_;
};

}  // namespace vantage
