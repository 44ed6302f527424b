#include "vantage/gain/models/surface_rates.hpp"

#include <stdexcept>

#include "vantage/gain/models/metrics/shared.hpp"
#include "vantage/gain/snapshot.hpp"
#include "vantage/util/text.hpp"

namespace vantage {

SurfaceRateFit::SurfaceRateFit(double recency, double prior_cells)
    : recency_(recency), prior_cells_(prior_cells) {
  if (!(recency > 0.0 && recency <= 1.0)) {
    throw std::invalid_argument(cat("surface rate fit: recency must lie in (0, 1], got ", recency));
  }
  if (!(prior_cells >= 0.0)) {
    throw std::invalid_argument(
        cat("surface rate fit: prior_cells must be >= 0 cells, got ", prior_cells));
  }
}

void SurfaceRateFit::before(const OccupancyGrid& grid, int num_threads) {
  const GainMap map(grid, num_threads);
  const std::vector<float> near = occupied_distance(map, kProximityCells);
  class_.assign(grid.size(), kNotNoted);
  for (std::size_t i = 0; i < class_.size(); ++i) {
    if (grid.is_unobserved(i)) class_[i] = static_cast<std::uint8_t>(surface_class(near[i]));
  }
}

void SurfaceRateFit::after(const OccupancyGrid& grid) {
  if (class_.size() != grid.size()) {
    throw std::logic_error("surface rate fit: after() without before() on a grid of its size");
  }
  std::array<double, kSurfaceClasses> known{}, occupied{};
  for (std::size_t i = 0; i < class_.size(); ++i) {
    if (class_[i] == kNotNoted) continue;
    const CellState state = grid.state(i);
    if (state == CellState::kUnobserved) continue;
    known[class_[i]] += 1.0;
    if (state == CellState::kOccupied) occupied[class_[i]] += 1.0;
  }
  for (std::size_t k = 0; k < kSurfaceClasses; ++k) {
    known_[k] = recency_ * known_[k] + known[k];
    occupied_[k] = recency_ * occupied_[k] + occupied[k];
    if (known_[k] + prior_cells_ > 0.0) {
      rates_[k] = (occupied_[k] + prior_cells_ * kSurfacePrior[k]) / (known_[k] + prior_cells_);
    }
  }
  class_.clear();
}

}  // namespace vantage
