#pragma once
/// @file
/// The surface model's chances fitted online from the run's own scans (issue 37; docs/model.md
/// "The surface model"), as the survival reading's a is (planner/observability.hpp).
///
/// Before a scan is integrated, each unobserved cell's distance class (surface_class) is noted;
/// after it, each class's cells that the scan turned known are counted, and those of them it
/// turned occupied. A class's rate is the share occupied, older scans weighing less, with a prior
/// of `prior_cells` cells at kSurfacePrior so that a class no scan has reached keeps the prior.

#include <array>
#include <cstdint>
#include <vector>

#include "vantage/gain/types.hpp"
#include "vantage/map/occupancy_grid.hpp"

namespace vantage {

class SurfaceRateFit {
 public:
  /// `recency` in (0, 1]: the weight of an outcome relative to the one after it; `prior_cells`
  /// >= 0: the prior's weight [cells]. Throws std::invalid_argument naming the value.
  explicit SurfaceRateFit(double recency = 0.5, double prior_cells = 100.0);

  /// Notes the distance class of every unobserved cell of `grid`, the map a scan is about to be
  /// integrated into.
  void before(const OccupancyGrid& grid, int num_threads = 0);
  /// Counts what the scan made of the cells noted (the same grid, the scan integrated) and
  /// updates the rates. Throws std::logic_error without a `before` on a grid of its size.
  void after(const OccupancyGrid& grid);

  /// The chances in force: kSurfacePrior until the first outcome.
  const SurfaceRates& rates() const { return rates_; }
  /// Per class, the weighted cells turned known so far [cells].
  const std::array<double, kSurfaceClasses>& known() const { return known_; }

 private:
  static constexpr std::uint8_t kNotNoted = 0xff;
  double recency_, prior_cells_;
  std::vector<std::uint8_t> class_;  ///< per cell: its class before the scan, or kNotNoted
  std::array<double, kSurfaceClasses> known_{}, occupied_{};
  SurfaceRates rates_ = kSurfacePrior;
};

}  // namespace vantage
