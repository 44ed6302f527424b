#include "vantage/gain/ray_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "vantage/map/line_of_sight.hpp"
#include "vantage/map/occupancy_grid.hpp"
#include "vantage/util/text.hpp"

namespace vantage {

double entropy_bits(double p) {
  if (p <= 0.0 || p >= 1.0) return 0.0;
  return -(p * std::log2(p) + (1.0 - p) * std::log2(1.0 - p));
}

RayModel::RayModel(double alpha) : alpha_(alpha) {
  if (!(alpha > 0.0 && alpha <= 1.0)) {
    throw std::invalid_argument(cat("alpha must lie in (0, 1], got ", alpha));
  }
}

RayState RayModel::start(double p0) {
  RayState s;
  s.m = 0;
  s.t = 1.0;
  s.visibility = 1.0;  // the origin's cell is visible
  s.posterior = p0;
  s.occupancy = p0;
  return s;
}

RayState RayModel::step(const RayState& prev, double p_m) const {
  RayState s;
  s.m = prev.m + 1;
  s.t = prev.t * alpha_;  // t_m = a^m, eq. (10)
  const double v = prev.visibility;
  const double p_prev = prev.occupancy;

  // Visibility HMM. Predict with the transition matrix of eq. (9), eq. (5) ...
  double vis = s.t * v + 0.1 * (1.0 - v);
  double hid = (1.0 - s.t) * v + 0.9 * (1.0 - v);
  // ... update with the cell just passed, eqs. (6)–(7): p(o|visible) ∝ 1 - p, p(o|hidden) ∝ p.
  vis *= 1.0 - p_prev;
  hid *= p_prev;
  s.visibility = (vis + hid) > 0.0 ? vis / (vis + hid) : 0.0;

  // Occupancy filter. Predict with the visibility-dependent transition, eqs. (14)–(15) ...
  const double tau = 0.5 + s.visibility / 2.0;
  const double pred = tau * prev.posterior + (1.0 - tau) * (1.0 - prev.posterior);
  // ... update with the measurement the map predicts, eq. (12).
  const double occ = pred * p_m;
  const double free = (1.0 - pred) * (1.0 - p_m);
  s.posterior = (occ + free) > 0.0 ? occ / (occ + free) : 0.5;
  s.occupancy = p_m;
  return s;
}

std::vector<RayState> RayModel::trace(std::span<const double> occupancy) const {
  if (occupancy.empty()) throw std::invalid_argument("a ray needs at least one cell");
  for (std::size_t i = 0; i < occupancy.size(); ++i) {
    if (!(occupancy[i] >= 0.0 && occupancy[i] <= 1.0)) {
      throw std::invalid_argument(
          cat("cell ", i, " has occupancy ", occupancy[i], "; probabilities must lie in [0, 1]"));
    }
  }
  std::vector<RayState> states;
  states.reserve(occupancy.size());
  states.push_back(start(occupancy[0]));
  for (std::size_t i = 1; i < occupancy.size(); ++i) {
    states.push_back(step(states.back(), occupancy[i]));
  }
  return states;
}

UniformPrefix::UniformPrefix(const RayModel& model, double p, int max_cells) {
  states_.reserve(static_cast<std::size_t>(std::max(max_cells, 1)));
  states_.push_back(RayModel::start(p));
  while (size() < max_cells) states_.push_back(model.step(states_.back(), p));
}

bool greedy_visible(std::span<const double> occupancy) {
  if (occupancy.empty()) return true;
  return std::none_of(occupancy.begin(), occupancy.end() - 1,
                      [](double p) { return occludes(classify(p)); });
}

}  // namespace vantage
