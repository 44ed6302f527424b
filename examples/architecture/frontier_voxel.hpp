#pragma once
/// @file
/// docs/architecture.md, "Add a model": a metric in its own file, as vantage/gain/models/metrics/
/// holds them. To make it a method, this file goes to
/// vantage/gain/models/metrics/frontier_voxel.hpp and one row goes to the registry,
/// vantage/gain/methods.cpp:
///
///   metric<FrontierVoxel>(GainMethod::kFrontierVoxel, "frontier-voxel"),
///
/// naming the enum value it adds to GainMethod (vantage/gain/types.hpp) and, to be chosen by
/// name, to PlannerMethod (vantage/planner/types.hpp). tests/architecture/worked_examples_test.cpp
/// compiles this file and holds it to its definition.

#include "vantage/gain/models/metric_type.hpp"

namespace vantage {

/// Frontier voxel: the unobserved cells a ray enters straight from a free one, the edge of the
/// known free space each view would look across [cells].
struct FrontierVoxel {
  double sum = 0.0;
  bool after_free = false;
  void begin_ray() { after_free = false; }
  void cell(const RayCell& c, Stamp& s) {
    if (c.in_range && unknown(c) && after_free && s.take(c.linear)) sum += 1.0;
    after_free = c.value.state == CellState::kFree;
  }
  void end_ray(bool, Stamp&) {}
  double value(double) const { return sum; }
};

}  // namespace vantage
