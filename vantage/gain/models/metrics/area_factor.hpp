#pragma once
/// @file
/// One of the field's volumetric metrics (docs/model.md "The field's metrics"),
/// as a metric type (models/metric_type.hpp); registered in gain/methods.cpp.

#include "vantage/gain/models/metric_type.hpp"
#include "vantage/gain/models/metrics/shared.hpp"

namespace vantage {

/// Vasquez-Gomez's area factor (eq. M7): each ray is registered once, at its first cell that is
/// occupied (counted when seen from free space, its front) or an "occplane" cell (unobserved,
/// within D of an occupied cell); rays that register neither are unmarked. With x_o and x_p the
/// fractions of all the view's rays registered occupied and occplane,
/// G = f(x_o; 0.2) + f(x_p; 0.8).
struct AreaFactor {
  static constexpr bool kFreeInert = true;
  double occupied = 0.0, occplane = 0.0;
  bool previous_free = true, registered = false;
  void begin_ray() {
    previous_free = true;  // the cells outside the grid are free (docs/model.md)
    registered = false;
  }
  void cell(const RayCell& c, Stamp&) {
    if (registered || !c.in_range) {
      previous_free = c.value.state == CellState::kFree;
      return;
    }
    if (unknown(c) && c.near <= kProximityCells) {
      occplane += 1.0;
      registered = true;
    } else if (c.value.state == CellState::kOccupied) {
      if (previous_free) occupied += 1.0;
      registered = true;
    }
    previous_free = c.value.state == CellState::kFree;
  }
  void end_ray(bool, Stamp&) {}
  double value(double rays) const {
    if (rays <= 0.0) return 0.0;
    return area_factor(occupied / rays, kAreaOccupied) +
           area_factor(occplane / rays, kAreaOccplane);
  }
};

}  // namespace vantage
