#pragma once
/// @file
/// One of the field's volumetric metrics (docs/model.md "The field's metrics"),
/// as a metric type (models/metric_type.hpp); registered in gain/methods.cpp.

#include <cstddef>
#include <utility>
#include <vector>

#include "vantage/gain/models/metric_type.hpp"

namespace vantage {

/// Rear side entropy: I_n(x) = P_v(x) I(x) for the unobserved cells on rays that end on a rear
/// side, else 0 (eq. M4).
struct RearSideEntropy {
  static constexpr bool kFreeDims = true;      // free cells credit nothing; they dim the later ones
  static constexpr bool kRearSideRays = true;  // it credits nothing on the others
  // NOTE: no visibility floor past which a ray's cells are ignored: its values fall to 1e-5 bits
  // and below as a table top is explored, where a floor of 1e-6 changed tabletop-4's decision.
  double sum = 0.0;
  std::vector<std::pair<std::size_t, double>> pending;  // this ray's unobserved cells, P_v I
  void begin_ray() { pending.clear(); }
  void cell(const RayCell& c, Stamp&) {
    if (c.in_range && unknown(c)) {
      pending.emplace_back(c.linear, c.weight * c.visibility * c.value.entropy);
    }
  }
  void end_ray(bool rear_side, Stamp& s) {
    if (!rear_side) return;
    for (const auto& [linear, gain] : pending) {
      if (s.take(linear)) sum += gain;
    }
  }
  double value(double) const { return sum; }
};

}  // namespace vantage
