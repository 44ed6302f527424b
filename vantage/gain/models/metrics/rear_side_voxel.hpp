#pragma once
/// @file
/// One of the field's volumetric metrics (docs/model.md "The field's metrics"),
/// as a metric type (models/metric_type.hpp); registered in gain/methods.cpp.

#include "vantage/gain/models/metric_type.hpp"

namespace vantage {

/// Rear side voxel: I_b(x) = 1 if x is an occupied cell that its ray reaches straight from an
/// unobserved cell, a rear side of a surface seen before (eq. M3), else 0.
struct RearSideVoxel {
  static constexpr bool kFreeInert = true;
  static constexpr bool kRearSideRays = true;  // it credits nothing on the others
  // NOTE: no cubes of unobserved cells alone (after one, more change nothing): tried, they cost
  // as much as they saved on tabletop-4's hemisphere (BENCHMARK.md, "The metrics raced"); the
  // probe of rear side rays crosses cubes of free and unobserved cells alike.
  double sum = 0.0;
  bool previous_unknown = false;
  void begin_ray() { previous_unknown = false; }
  void cell(const RayCell& c, Stamp& s) {
    if (c.value.state == CellState::kOccupied && previous_unknown && c.in_range &&
        s.take(c.linear)) {
      sum += c.weight;
    }
    previous_unknown = unknown(c);
  }
  void end_ray(bool, Stamp&) {}
  double value(double) const { return sum; }
};

}  // namespace vantage
