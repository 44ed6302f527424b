#pragma once
/// @file
/// One of the field's volumetric metrics (docs/model.md "The field's metrics"),
/// as a metric type (models/metric_type.hpp); registered in gain/methods.cpp.

#include "vantage/gain/models/metric_type.hpp"

namespace vantage {

/// Average entropy (Kriegel et al. 2015): G = sum_{x in X} I(x) / |X| over the set X of cells
/// the rays traverse (eq. M6).
struct AverageEntropy {
  double sum = 0.0, count = 0.0;
  void begin_ray() {}
  void cell(const RayCell& c, Stamp& s) {
    if (c.in_range && s.take(c.linear)) {
      sum += c.weight * c.value.entropy;
      count += c.weight;
    }
  }
  void end_ray(bool, Stamp&) {}
  double value(double) const { return count > 0.0 ? sum / count : 0.0; }
};

}  // namespace vantage
