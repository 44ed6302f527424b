#pragma once
/// @file
/// The surface model (issue 37, docs/model.md "The surface model"), as a metric type of
/// models/metric_type.hpp; registered in gain/methods.cpp.

#include "vantage/gain/models/metric_type.hpp"
#include "vantage/gain/models/metrics/shared.hpp"

namespace vantage {

/// The surface a view's rays reach first near the surface already known: the survival reading
/// (survival.hpp) on the metrics' pinhole rays, with a chance per unobserved cell that it holds a
/// surface, r(x), taken by its distance to the nearest occupied cell (surface_class,
/// GainConfig::surface_rates). Along a ray the visibility is v(x_n) = prod_{i<n} (1 - r(x_i))
/// over the unobserved cells before x_n (free cells pass it, an occupied one ends it), and the
/// view's value is
///   sum over the unobserved cells x within D of an occupied cell its rays reach, once each, of
///   v(x) r(x),
/// the expected number of cells next to the known surface that its scan turns occupied: the
/// surface it adds, which the yardstick's coverage counts. The far class dims the rays but
/// credits nothing: credited, its many cells at a small rate outweighed the near classes and the
/// model ranked views as the counts do (docs/model.md, "The surface model"). Greedy and the
/// unobserved-voxel metric count every reachable cell alike; the survival reading gives every
/// cell one chance 1 - a.
struct Surface {
  static constexpr bool kFreeInert = true;
  static constexpr bool kNearRays = true;  // the far class dims, but a ray of it alone credits 0
  static constexpr bool kCellSum = true;   // models/metric_cells.hpp
  static constexpr bool kFarAlike = true;  // a far cell dims by its class's rate, credits nothing
  static constexpr bool kSurfaceCells = true;  // its value in cells, its rates fitted by a run
  explicit Surface(const detail::MetricContext& ctx) : rates(ctx.surface_rates) {}
  SurfaceRates rates;
  double sum = 0.0;
  double v = 1.0;
  void begin_ray() { v = 1.0; }
  [[gnu::always_inline]] void cell(const RayCell& c, Stamp& s) {
    if (!unknown(c)) return;
    const std::size_t k = surface_class(c.near);
    const double r = rates[k];
    if (k + 1 < kSurfaceClasses && c.in_range) s.add(c.linear, c.weight * v * r, sum);
    v *= 1.0 - r;
  }
  void end_ray(bool, Stamp&) {}
  double value(double) const { return sum; }
};

}  // namespace vantage
