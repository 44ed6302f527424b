#pragma once
/// @file
/// One of the field's volumetric metrics (docs/model.md "The field's metrics"),
/// as a metric type (models/metric_type.hpp); registered in gain/methods.cpp.

#include "vantage/gain/models/metric_type.hpp"
#include "vantage/gain/models/metrics/shared.hpp"

namespace vantage {

/// Proximity count: I_p(x) = D - d(x) for an unobserved cell x within distance d(x) <= D of an
/// occupied cell, else 0 (eq. M5): unobserved cells near a surface, the nearer the more.
struct ProximityCount {
  static constexpr bool kFreeInert = true;
  static constexpr detail::QuietCells kQuiet = detail::QuietCells::kFar;  // they credit nothing
  static constexpr bool kNearRays = true;
  static constexpr bool kCellSum = true;  // models/metric_cells.hpp
  double sum = 0.0;
  void begin_ray() {}
  void cell(const RayCell& c, Stamp& s) {
    if (c.in_range && unknown(c) && c.near <= kProximityCells) {
      s.add(c.linear, c.weight * (kProximityCells - c.near), sum);
    }
  }
  void end_ray(bool, Stamp&) {}
  double value(double) const { return sum; }
};

}  // namespace vantage
