#include "vantage/gain/survival.hpp"

#include <algorithm>
#include <stdexcept>

#include "vantage/gain/ray_model.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// The paper's occupancy filter, eqs. (14), (15), (12): the prediction keeps q with tau = 0.5 +
/// v / 2, the update is the map's occupancy p of the cell.
double filter(double q, double v, double p) {
  const double tau = 0.5 + 0.5 * v;
  const double pred = tau * q + (1.0 - tau) * (1.0 - q);
  const double occ = pred * p, free = (1.0 - pred) * (1.0 - p);
  return occ + free > 0.0 ? occ / (occ + free) : 0.5;
}

}  // namespace

SurvivalModel::SurvivalModel(double alpha, double p_min, int max_cells) : alpha_(alpha) {
  if (!(alpha > 0.0 && alpha <= 1.0)) {
    throw std::invalid_argument(cat("survival alpha must lie in (0, 1], got ", alpha));
  }
  double q = p_min;  // c_0, the origin's cell
  outside_.reserve(static_cast<std::size_t>(std::max(0, max_cells)) + 1);
  outside_.push_back(q);
  for (int k = 1; k <= max_cells; ++k) {
    q = filter(q, 1.0, p_min);  // free cells keep v = 1
    outside_.push_back(q);
  }
}

SurvivalModel::State SurvivalModel::enter(int m, const GainMap::Value& cell) const {
  if (m == 0) return {1.0, cell.p};
  return {1.0, filter(outside_.at(static_cast<std::size_t>(m - 1)), 1.0, cell.p)};
}

void SurvivalModel::step(State& s, const GainMap::Value& prev, const GainMap::Value& cell) const {
  switch (prev.state) {  // eqs. (9)-(10), the survival reading: stay visible past c_{m-1}
    case CellState::kOccupied:
      s.visibility = 0.0;
      break;
    case CellState::kUnobserved:
      s.visibility *= alpha_;
      break;
    case CellState::kFree:
      break;
  }
  s.posterior = filter(s.posterior, s.visibility, cell.p);
}

TargetPrediction SurvivalModel::predict(const State& s, const GainMap::Value& target) {
  return {target.entropy - entropy_bits(s.posterior), s.visibility};
}

}  // namespace vantage
