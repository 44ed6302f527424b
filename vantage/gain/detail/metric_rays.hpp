#pragma once
/// @file
/// The ray casting the field's metrics share (metrics.hpp): a pinhole image of rays per view, each
/// walked until its first occupied cell, feeding a metric type. A metric type has
///   void begin_ray();
///   void cell(const RayCell&, Stamp& credit);   // every cell the ray crosses, in order
///   void end_ray(bool rear_side, Stamp& credit);
///   double value(double rays) const;            // once all of a view's rays are cast
/// and lives in its own file under gain/metrics/; gain/methods.cpp registers it.

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "vantage/gain/snapshot.hpp"
#include "vantage/gain/types.hpp"
#include "vantage/map/traversal.hpp"
#include "vantage/util/parallel.hpp"
#include "vantage/views/frustum.hpp"

namespace vantage {

// The definitions, equations and where rpg_ig_active_reconstruction's code differs from the
// paper: docs/model.md, "The field's metrics". Entropies are in bits (the paper's in nats: a
// constant factor, the same ranking).

/// A cell as a metric sees it on its ray.
struct RayCell {
  std::size_t linear;
  const GainMap::Value& value;
  double visibility;  ///< P_v: the product of 1 - p over the ray's cells before this one
  float near;         ///< distance to the nearest occupied cell [cells], +inf beyond D
  bool in_range;      ///< the cell's centre lies at least the sensor's min range away
};

/// Marks cells counted in the current view: one stamp array per thread, one id per view.
struct Stamp {
  std::vector<std::uint32_t>& marks;
  std::uint32_t id;
  /// True the first time a cell is taken in this view.
  bool take(std::size_t i) {
    if (marks[i] == id) return false;
    marks[i] = id;
    return true;
  }
};

inline bool unknown(const RayCell& c) { return c.value.state == CellState::kUnobserved; }

// Each metric below follows one view's rays: begin_ray(), cell() for every cell the ray crosses
// in order (the last one occupied when the ray ended on one), end_ray(rear_side), where
// rear_side says the ray ended on an occupied cell right behind an unobserved one; value() once
// all rays are cast. Cells are credited once per view (Stamp).

namespace detail {

/// What the metrics of one evaluation share.
struct MetricContext {
  const GainMap& map;
  const std::vector<float>& near;  // empty when the metric needs no distances
  double spacing;                  // ray pitch at the farthest cell in view [cells]
  int subsample;                   // cast every subsample-th ray along each image axis
};

/// Casts one view's rays and feeds them to `metric`; returns the metric's value and the count of
/// unobserved cells reached.
template <typename Metric>
ViewGain cast_view(const MetricContext& ctx, const Frustum& view, Metric& metric, Stamp& credit,
                   Stamp& seen) {
  const GridSpec& spec = ctx.map.spec();
  const SensorFov& fov = view.fov();
  const Eigen::Vector3d o = view.origin();
  const Eigen::Matrix3d R = view.T_world_sensor().linear();
  // The pitch: neighbouring rays `spacing` cells apart at the farthest corner of the grid.
  double depth = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p((corner & 1) ? spec.max_corner().x() : spec.origin.x(),
                            (corner & 2) ? spec.max_corner().y() : spec.origin.y(),
                            (corner & 4) ? spec.max_corner().z() : spec.origin.z());
    depth = std::max(depth, (p - o).norm());
  }
  depth = std::clamp(depth, spec.resolution, fov.max_range);
  const double du = ctx.spacing * spec.resolution / depth;
  const double tan_h = std::tan(fov.h_fov / 2.0), tan_v = std::tan(fov.v_fov / 2.0);
  const int cols = std::max(1, static_cast<int>(std::ceil(2.0 * tan_h / du)));
  const int rows = std::max(1, static_cast<int>(std::ceil(2.0 * tan_v / du)));
  const double su = 2.0 * tan_h / cols, sv = 2.0 * tan_v / rows;
  const double min_r2 = fov.min_range * fov.min_range;
  const float far = std::numeric_limits<float>::infinity();

  ViewGain result;
  double rays = 0.0;
  const int first = ctx.subsample / 2;
  for (int row = first; row < rows; row += ctx.subsample) {
    for (int col = first; col < cols; col += ctx.subsample) {
      rays += 1.0;
      const Eigen::Vector3d dir =
          (R * Eigen::Vector3d(1.0, -tan_h + (col + 0.5) * su, -tan_v + (row + 0.5) * sv))
              .normalized();
      metric.begin_ray();
      double visibility = 1.0;
      bool previous_unknown = false, rear_side = false;
      traverse(spec, o, o + fov.max_range * dir, [&](const Index3& cell, std::size_t linear, int) {
        const GainMap::Value& v = ctx.map.value(linear);
        const bool in_range = (spec.center(cell) - o).squaredNorm() >= min_r2;
        const RayCell c{linear, v, visibility, ctx.near.empty() ? far : ctx.near[linear], in_range};
        metric.cell(c, credit);
        if (in_range && unknown(c) && seen.take(linear)) result.cells += 1.0;
        if (v.state == CellState::kOccupied) {
          rear_side = previous_unknown;
          return false;  // the ray ends on its first occupied cell
        }
        previous_unknown = unknown(c);
        visibility *= 1.0 - v.p;  // eq. M1: P_v(x_{n+1}) = P_v(x_n) (1 - P_o(x_n))
        return true;
      });
      metric.end_ray(rear_side, credit);
    }
  }
  result.gain = metric.value(rays);
  result.targets = static_cast<std::size_t>(result.cells);
  return result;
}

/// Every view's value under `Metric`; views in parallel, each view's rays in order on one thread,
/// so the result does not depend on threads.
template <typename Metric>
std::vector<ViewGain> all_views(const MetricContext& ctx, std::span<const Frustum> views,
                                int num_threads) {
  std::vector<ViewGain> gains(views.size());
  struct Marks {
    std::vector<std::uint32_t> credit, seen;
  };
  const std::size_t cells = ctx.map.size();
  tbb::enumerable_thread_specific<Marks> marks([cells] {
    return Marks{std::vector<std::uint32_t>(cells, 0), std::vector<std::uint32_t>(cells, 0)};
  });
  run_with_threads(num_threads, [&] {
    tbb::parallel_for(std::size_t{0}, views.size(), [&](std::size_t v) {
      Marks& m = marks.local();
      const auto id = static_cast<std::uint32_t>(v + 1);
      Stamp credit{m.credit, id}, seen{m.seen, id};
      Metric metric;
      gains[v] = cast_view(ctx, views[v], metric, credit, seen);
    });
  });
  return gains;
}

}  // namespace detail
}  // namespace vantage
