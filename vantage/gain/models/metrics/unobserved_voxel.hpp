#pragma once
/// @file
/// One of the field's volumetric metrics (docs/model.md "The field's metrics"),
/// as a metric type (models/metric_type.hpp); registered in gain/methods.cpp.

#include "vantage/gain/models/metric_type.hpp"

namespace vantage {

/// Unobserved voxel: I_u(x) = 1 if x is unobserved, else 0 (eq. M2): the unobserved cells the
/// rays reach.
struct UnobservedVoxel {
  static constexpr bool kFreeInert = true;
  double sum = 0.0;
  void begin_ray() {}
  void cell(const RayCell& c, Stamp& s) {
    if (c.in_range && unknown(c) && s.take(c.linear)) sum += c.weight;
  }
  void end_ray(bool, Stamp&) {}
  double value(double) const { return sum; }
};

}  // namespace vantage
