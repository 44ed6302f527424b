#pragma once
/// @file
/// One of the field's volumetric metrics (docs/model.md "The field's metrics"),
/// as a metric type (models/metric_type.hpp); registered in gain/methods.cpp.

#include "vantage/gain/models/metric_type.hpp"

namespace vantage {

/// Occlusion aware: I_o(x) = P_v(x) I(x), P_v(x_n) = prod_{i<n} (1 - P_o(x_i)) (docs/model.md,
/// eq. M1): every cell's entropy weighted by the chance that it is seen.
struct OcclusionAware {
  // NOTE: no visibility floor past which a ray's cells are ignored: a cell a ray leaves
  // uncredited there is credited by a later ray of the view at its own visibility (the reference
  // credits the first ray's), which raised views' values on tabletop-4's hemisphere by up to 11 %.
  double sum = 0.0;
  void begin_ray() {}
  void cell(const RayCell& c, Stamp& s) {
    if (c.in_range && s.take(c.linear)) sum += c.weight * c.visibility * c.value.entropy;
  }
  void end_ray(bool, Stamp&) {}
  double value(double) const { return sum; }
};

}  // namespace vantage
