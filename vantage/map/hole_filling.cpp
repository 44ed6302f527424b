#include "vantage/map/hole_filling.hpp"

#include <cmath>
#include <stdexcept>

#include "vantage/util/text.hpp"

namespace vantage {

void HoleFillingConfig::validate() const {
  if (!(beta >= 0.0 && std::isfinite(beta))) {
    throw std::invalid_argument(cat("hole_filling.beta must be >= 0, got ", beta));
  }
  if (!(eta >= 0.0 && std::isfinite(eta))) {
    throw std::invalid_argument(cat("hole_filling.eta must be >= 0, got ", eta));
  }
  if (max_sweeps < 1) {
    throw std::invalid_argument(cat("hole_filling.max_sweeps must be >= 1, got ", max_sweeps));
  }
}

IcmField::IcmField(const OccupancyGrid& grid, double beta, double eta)
    : spec_(grid.spec()), beta_(beta), eta_(eta), s_(grid.size()), o_(grid.size()) {
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const CellState state = grid.state(i);
    o_[i] = s_[i] = state == CellState::kOccupied ? 1 : -1;
    if (state == CellState::kUnobserved) mutable_.push_back(static_cast<std::uint32_t>(i));
  }
}

double IcmField::local_field(std::size_t i) const {
  // beta * (sum of the neighbours' states) + eta * o: the state of lower energy has its sign.
  const Index3 c = spec_.unravel(i);
  const auto nx = static_cast<std::size_t>(spec_.dims.x());
  const std::size_t nxy = nx * static_cast<std::size_t>(spec_.dims.y());
  int sum = 0;
  if (c.x() > 0) sum += s_[i - 1];
  if (c.x() + 1 < spec_.dims.x()) sum += s_[i + 1];
  if (c.y() > 0) sum += s_[i - nx];
  if (c.y() + 1 < spec_.dims.y()) sum += s_[i + nx];
  if (c.z() > 0) sum += s_[i - nxy];
  if (c.z() + 1 < spec_.dims.z()) sum += s_[i + nxy];
  return beta_ * sum + eta_ * o_[i];
}

std::size_t IcmField::sweep() {
  std::size_t changed = 0;
  for (const std::uint32_t i : mutable_) {
    const double field = local_field(i);
    // NOTE: on a tie both states have equal energy; keeping the current one guarantees that
    // every change strictly lowers the energy, so ICM terminates.
    const std::int8_t best = field > 0.0 ? 1 : (field < 0.0 ? -1 : s_[i]);
    if (best != s_[i]) {
      s_[i] = best;
      ++changed;
    }
  }
  return changed;
}

double IcmField::energy() const {
  const auto nx = static_cast<std::size_t>(spec_.dims.x());
  const std::size_t nxy = nx * static_cast<std::size_t>(spec_.dims.y());
  double pairs = 0.0;
  double data = 0.0;
  for (std::size_t i = 0; i < s_.size(); ++i) {
    const Index3 c = spec_.unravel(i);
    if (c.x() + 1 < spec_.dims.x()) pairs += s_[i] * s_[i + 1];
    if (c.y() + 1 < spec_.dims.y()) pairs += s_[i] * s_[i + nx];
    if (c.z() + 1 < spec_.dims.z()) pairs += s_[i] * s_[i + nxy];
    data += s_[i] * o_[i];
  }
  return -beta_ * pairs - eta_ * data;  // eq. (21)
}

std::vector<std::uint32_t> IcmField::filled() const {
  std::vector<std::uint32_t> cells;
  for (const std::uint32_t i : mutable_) {
    if (s_[i] > 0) cells.push_back(i);
  }
  return cells;
}

HoleFillingResult fill_holes(OccupancyGrid& grid, const HoleFillingConfig& config) {
  config.validate();
  HoleFillingResult result;
  if (!config.enabled) return result;
  IcmField field(grid, config.beta, config.eta);
  for (;;) {
    if (result.sweeps == config.max_sweeps) {
      throw std::runtime_error(
          cat("hole filling did not converge in ", config.max_sweeps, " sweeps"));
    }
    ++result.sweeps;
    if (field.sweep() == 0) break;
  }
  result.filled = field.filled();
  for (const std::uint32_t i : result.filled) grid.hit(i);
  return result;
}

}  // namespace vantage
